#include "lib/util/logging.h"

#include <atomic>
#include <cstdio>
#include <stdexcept>

namespace lutex {
namespace {

std::atomic<int> g_log_level{static_cast<int>(LogLevel::kInfo)};

const char* LevelName(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug: return "debug";
    case LogLevel::kInfo: return "info";
    case LogLevel::kWarning: return "warning";
    case LogLevel::kError: return "error";
    case LogLevel::kSilent: return "silent";
  }
  return "?";
}

}  // namespace

void SetLogLevel(LogLevel level) { g_log_level = static_cast<int>(level); }

LogLevel GetLogLevel() { return static_cast<LogLevel>(g_log_level.load()); }

LogLevel ParseLogLevel(const std::string& name) {
  for (LogLevel level : {LogLevel::kDebug, LogLevel::kInfo, LogLevel::kWarning, LogLevel::kError,
                         LogLevel::kSilent}) {
    if (name == LevelName(level)) return level;
  }
  throw std::invalid_argument("unknown log level '" + name +
                              "' (expected debug, info, warning, error or silent)");
}

void LogMessage(LogLevel level, const std::string& message) {
  if (static_cast<int>(level) < g_log_level.load() || level == LogLevel::kSilent) return;
  const std::string line = std::string("[lutex ") + LevelName(level) + "] " + message + "\n";
  std::fputs(line.c_str(), stderr);
}

}  // namespace lutex
