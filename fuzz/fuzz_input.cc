#include "fuzz/fuzz_input.h"

#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <system_error>

#include "lib/util/logging.h"

namespace lutex {
namespace {

// Removes the folder when the process exits normally (libFuzzer ends a run with exit()).
struct OwnedFolder {
  std::filesystem::path path;
  OwnedFolder() {
    path = std::filesystem::temp_directory_path() / ("lutex_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(path);
  }
  ~OwnedFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

const std::filesystem::path& FuzzFolder() {
  static const OwnedFolder folder;
  return folder.path;
}

std::filesystem::path WriteFuzzFile(const std::string& name, const std::string& bytes) {
  const std::filesystem::path path = FuzzFolder() / name;
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.close();
  if (!file) throw std::logic_error("fuzz target: cannot write " + path.string());  // not the reader's fault
  return path;
}

std::string FuzzBytes(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

std::vector<std::string> SplitFuzzInput(const std::string& input, std::size_t max_parts) {
  const std::string separator = kFuzzFileSeparator;
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (parts.size() + 1 < max_parts) {
    const std::size_t end = input.find(separator, begin);
    if (end == std::string::npos) break;
    parts.push_back(input.substr(begin, end - begin));
    begin = end + separator.size();
  }
  parts.push_back(input.substr(begin));
  return parts;
}

std::filesystem::path WriteFuzzFolder(const std::string& folder, const std::string& input,
                                      const std::vector<std::string>& names) {
  const std::filesystem::path path = FuzzFolder() / folder;
  std::filesystem::create_directories(path);
  const std::vector<std::string> parts = SplitFuzzInput(input, names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i < parts.size()) {
      WriteFuzzFile(folder + "/" + names[i], parts[i]);
    } else {
      std::filesystem::remove(path / names[i]);
    }
  }
  return path;
}

}  // namespace lutex

// libFuzzer calls this once before the first input: the readers' log lines (a skipped target, dropped
// degenerate faces) would only slow the run down.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  lutex::SetLogLevel(lutex::LogLevel::kSilent);
  return 0;
}
