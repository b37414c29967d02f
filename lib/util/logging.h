#pragma once

// Minimal levelled logging to stderr. Messages are whole lines; a line is written with one call so that
// lines from different threads do not interleave.

#include <sstream>
#include <string>

namespace lutex {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarning = 2, kError = 3, kSilent = 4 };

// Messages below this level are dropped. Default: kInfo.
void SetLogLevel(LogLevel level);
LogLevel GetLogLevel();

// Parses "debug", "info", "warning", "error" or "silent"; throws std::invalid_argument otherwise.
LogLevel ParseLogLevel(const std::string& name);

// Writes "[lutex LEVEL] message" on stderr when `level` is enabled.
void LogMessage(LogLevel level, const std::string& message);

// Stream-style helpers: LogInfo() << "read " << n << " images";  (the line is written at the end of the
// full expression).
class LogLine {
 public:
  explicit LogLine(LogLevel level) : level_(level) {}
  ~LogLine() { LogMessage(level_, stream_.str()); }
  LogLine(const LogLine&) = delete;
  LogLine& operator=(const LogLine&) = delete;
  template <typename T>
  LogLine& operator<<(const T& value) {
    stream_ << value;
    return *this;
  }

 private:
  LogLevel level_;
  std::ostringstream stream_;
};

inline LogLine LogDebug() { return LogLine(LogLevel::kDebug); }
inline LogLine LogInfo() { return LogLine(LogLevel::kInfo); }
inline LogLine LogWarning() { return LogLine(LogLevel::kWarning); }

}  // namespace lutex
