#pragma once

// Runs a measurement in a child process that does nothing else, so its peak resident set is its own (not
// that of the simulation or of the measurements before it). `Measurement` is trivially copyable (it
// crosses a pipe) and has a `double peak_mib`, which this fills.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>
#include <stdexcept>
#include <type_traits>

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

}  // namespace lutex::bench
