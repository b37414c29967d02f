#pragma once

// What every benchmark needs: a stopwatch and `--name value` integer options.

#include <chrono>
#include <cstdlib>
#include <cstring>

namespace lutex::bench {

inline double SecondsSince(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline int IntOption(int argc, char** argv, const char* name, int fallback) {
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], name) == 0) return std::atoi(argv[i + 1]);
  }
  return fallback;
}

}  // namespace lutex::bench
