#pragma once

// What to tell the user when writing a file failed. A full disk during a night's restore is the common
// case and deserves to be named as such, with the file being written, instead of a library's guess ("does
// the extension suit its bit depth?") or its raw line.

#include <filesystem>
#include <string>

namespace lutex {

// "PATH: the disk is full (12 KiB free on the file system of FOLDER)" when `error_number` is ENOSPC or
// EDQUOT or the file system of `path` has less than 1 MiB free; else "PATH: cannot be written (REASON)",
// REASON being strerror(error_number), or `fallback` when error_number is 0.
std::string DescribeWriteFailure(const std::filesystem::path& path, int error_number, const std::string& fallback);

}  // namespace lutex
