#pragma once

// What every benchmark needs: a stopwatch and `--name value` integer options.
//
//   bench::Options args(argc, argv, "mosaic_benchmark [--runs 1] [--keep 0]");
//   const int runs = args.Int("--runs", 1);
//   const bool keep = args.Int("--keep", 0) != 0;
//   args.CheckAllRead();
//
// `--help` (or `-h`) prints the usage and where the options are described, and exits 0. An
// option the benchmark does not read, one without a value or with a value that is not an integer prints
// one line naming it and the usage, and exits 2: a mistyped option is not silently left at its default.

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace lutex::bench {

inline double SecondsSince(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class Options {
 public:
  // `usage`: the benchmark's name and options, as its source's header shows them.
  Options(int argc, char** argv, std::string usage) : args_(argv + 1, argv + argc), usage_(std::move(usage)) {
    for (const std::string& arg : args_) {
      if (arg == "--help" || arg == "-h") {
        std::printf("usage: %s\n(each option takes an integer; bench/ in the source says what they do and how the "
                    "README uses them)\n",
                    usage_.c_str());
        std::exit(0);
      }
    }
  }

  // The value after `name`, or `fallback` when it is not given.
  int Int(const char* name, int fallback) {
    read_.push_back(name);
    for (std::size_t i = 0; i + 1 < args_.size(); i += 2) {
      if (args_[i] != name) continue;
      char* end = nullptr;
      const long value = std::strtol(args_[i + 1].c_str(), &end, 10);
      if (args_[i + 1].empty() || *end != '\0') Fail(std::string(name) + " takes an integer, not '" + args_[i + 1] + "'");
      return static_cast<int>(value);
    }
    return fallback;
  }

  // After every Int: exits 2 on an option not read or without a value.
  void CheckAllRead() const {
    for (std::size_t i = 0; i < args_.size(); i += 2) {
      bool known = false;
      for (const std::string& name : read_) known = known || args_[i] == name;
      if (!known) Fail("unknown option '" + args_[i] + "'");
      if (i + 1 >= args_.size()) Fail(args_[i] + " needs a value");
    }
  }

 private:
  [[noreturn]] void Fail(const std::string& problem) const {
    std::fprintf(stderr, "%s\nusage: %s\n", problem.c_str(), usage_.c_str());
    std::exit(2);
  }

  std::vector<std::string> args_;
  std::string usage_;
  std::vector<std::string> read_;
};

}  // namespace lutex::bench
