#pragma once

// Progress of long work (images done / total, rate, ETA) on stderr. On a terminal it redraws one line;
// otherwise (logs, CI) it writes a plain log line at most every `log_interval_seconds` and at the end.
// Thread-safe: workers call Advance() from any thread.

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace lutex {

class ProgressReporter {
 public:
  // `what` names the work ("raycast"), `unit` the items ("images").
  ProgressReporter(std::string what, std::size_t total, std::string unit, double log_interval_seconds = 10.0);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void Advance(std::size_t count = 1);
  // Writes the final line (also called by the destructor if not called before).
  void Finish();

  // "12/40 images, 3.1 images/s, ETA 9 s" for the given state; exposed for tests.
  static std::string FormatStatus(std::size_t done, std::size_t total, const std::string& unit,
                                  double elapsed_seconds);

 private:
  void Report(bool final_line);

  std::string what_;
  std::size_t total_;
  std::string unit_;
  double log_interval_seconds_;
  bool to_terminal_;
  std::size_t done_ = 0;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_report_;
  std::mutex mutex_;
};

}  // namespace lutex
