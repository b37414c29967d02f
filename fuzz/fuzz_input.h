#pragma once

// What every fuzz target shares: the readers take paths, so a target writes libFuzzer's bytes as files in
// a folder of its own process (under TMPDIR, removed when the process exits), and a target whose reader
// reads several files (a sparse model) splits its input into them at a separator line.
//
// A reader's clear error is the right answer to bad bytes; the targets catch std::runtime_error and
// std::invalid_argument (the exceptions the readers document) and let everything else through, so an
// unexpected exception type (std::bad_alloc, std::out_of_range, a JSON library's own) is reported by
// libFuzzer like a crash, as are sanitizer reports, leaks, timeouts and running out of memory.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lutex {

// The folder of this process, created on first use.
const std::filesystem::path& FuzzFolder();

// Writes `bytes` to FuzzFolder() / name (replacing what was there) and returns the path.
std::filesystem::path WriteFuzzFile(const std::string& name, const std::string& bytes);

// The input as text.
std::string FuzzBytes(const std::uint8_t* data, std::size_t size);

// The input cut at each kFuzzFileSeparator into at most `max_parts` parts (the last part keeps any
// further separators). Seeds of multi-file targets are the files joined with the separator.
inline constexpr const char* kFuzzFileSeparator = "\n=====lutex-fuzz-next-file=====\n";
std::vector<std::string> SplitFuzzInput(const std::string& input, std::size_t max_parts);

// The input split as above into the files `names` of the folder FuzzFolder() / `folder` (created); a file
// the input lacks is absent from it. Returns the folder.
std::filesystem::path WriteFuzzFolder(const std::string& folder, const std::string& input,
                                      const std::vector<std::string>& names);

}  // namespace lutex
