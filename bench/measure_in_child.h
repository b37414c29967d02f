#pragma once

// Runs a measurement in a child process that does nothing else, so its peak resident set is its own (not
// that of the simulation or of the measurements before it). `Measurement` is trivially copyable (it
// crosses a pipe) and has a `double peak_mib`, which this fills.
//
// The peak of a multi-threaded stage varies from run to run by a tenth or so (which of two threads' large
// buffers overlap, where the allocator finds room): a ratio of two single runs' peaks is not a
// measurement. InChildren repeats the work and gives the medians and the spread.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace lutex::bench {

template <typename Measurement>
Measurement InChild(const std::function<Measurement()>& work) {
  static_assert(std::is_trivially_copyable_v<Measurement>);
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) throw std::runtime_error("pipe failed");
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_ends[0]);
    Measurement measurement = work();
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    measurement.peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;
    if (write(pipe_ends[1], &measurement, sizeof(measurement)) != sizeof(measurement)) _exit(1);
    _exit(0);
  }
  close(pipe_ends[1]);
  Measurement measurement{};
  const bool complete = read(pipe_ends[0], &measurement, sizeof(measurement)) == sizeof(measurement);
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (!complete || status != 0) throw std::runtime_error("the measurement failed");
  return measurement;
}

// The lowest and highest peak of repeated runs.
struct PeakSpread {
  double lowest_mib = 0.0;
  double highest_mib = 0.0;
};

// `runs` (at least 1) runs of `work`, each in its own child: the run whose peak is the median (the upper
// one of two middle values), with `seconds` (which Measurement has) the median of the runs' seconds.
template <typename Measurement>
Measurement InChildren(int runs, const std::function<Measurement()>& work, PeakSpread* spread) {
  std::vector<Measurement> measured;
  for (int run = 0; run < std::max(runs, 1); ++run) measured.push_back(InChild<Measurement>(work));
  std::vector<double> seconds;
  for (const Measurement& m : measured) seconds.push_back(m.seconds);
  std::sort(seconds.begin(), seconds.end());
  std::sort(measured.begin(), measured.end(),
            [](const Measurement& a, const Measurement& b) { return a.peak_mib < b.peak_mib; });
  spread->lowest_mib = measured.front().peak_mib;
  spread->highest_mib = measured.back().peak_mib;
  Measurement median = measured[measured.size() / 2];
  median.seconds = seconds[seconds.size() / 2];
  return median;
}

}  // namespace lutex::bench
