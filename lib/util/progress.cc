#include "lib/util/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "lib/util/logging.h"

namespace lutex {

ProgressReporter::ProgressReporter(std::string what, std::size_t total, std::string unit,
                                   double log_interval_seconds)
    : what_(std::move(what)),
      total_(total),
      unit_(std::move(unit)),
      log_interval_seconds_(log_interval_seconds),
      to_terminal_(isatty(STDERR_FILENO) == 1 && GetLogLevel() <= LogLevel::kInfo),
      start_(std::chrono::steady_clock::now()),
      last_report_(start_) {}

ProgressReporter::~ProgressReporter() { Finish(); }

std::string ProgressReporter::FormatStatus(std::size_t done, std::size_t total, const std::string& unit,
                                           double elapsed_seconds) {
  std::ostringstream out;
  out << done << "/" << total << " " << unit;
  if (elapsed_seconds > 0.0 && done > 0) {
    const double rate = static_cast<double>(done) / elapsed_seconds;
    out.precision(rate < 10 ? 2 : 0);
    out << std::fixed << ", " << rate << " " << unit << "/s";
    if (done < total) {
      const double eta = static_cast<double>(total - done) / rate;
      out.precision(0);
      out << ", ETA " << std::ceil(eta) << " s";
    } else {
      out.precision(1);
      out << ", " << elapsed_seconds << " s";
    }
  }
  return out.str();
}

void ProgressReporter::Advance(std::size_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  done_ += count;
  const auto now = std::chrono::steady_clock::now();
  const double since_last = std::chrono::duration<double>(now - last_report_).count();
  if (to_terminal_ ? since_last >= 0.2 : since_last >= log_interval_seconds_) {
    last_report_ = now;
    Report(false);
  }
}

void ProgressReporter::Finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  Report(true);
}

void ProgressReporter::Report(bool final_line) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string status = what_ + ": " + FormatStatus(done_, total_, unit_, elapsed);
  if (to_terminal_) {
    std::fprintf(stderr, "\r\033[K%s%s", status.c_str(), final_line ? "\n" : "");
    std::fflush(stderr);
  } else {
    LogInfo() << status;
  }
}

}  // namespace lutex
