#include "lib/util/memory_budget.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

// gperftools' C entry point (gperftools/malloc_extension_c.h); null unless tcmalloc is linked.
extern "C" int MallocExtension_GetNumericProperty(const char* property, std::size_t* value) __attribute__((weak));

namespace lutex {

std::size_t AvailableMemoryBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::size_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024 + AllocatorFreeBytes();
  }
  return 0;
}

std::size_t AllocatorFreeBytes() {
  std::size_t bytes = 0;
  if (MallocExtension_GetNumericProperty == nullptr) return 0;
  return MallocExtension_GetNumericProperty("tcmalloc.pageheap_free_bytes", &bytes) ? bytes : 0;
}

std::size_t ResolveMemoryLimit(std::size_t limit_bytes) {
  return limit_bytes != 0 ? limit_bytes : AvailableMemoryBytes();
}

void MemoryEstimate::Add(const std::string& what, double count, double bytes_each) {
  const double bytes = count * bytes_each;
  parts_.push_back({what, bytes});
  total_bytes_ += bytes;
}

std::string MemoryEstimate::Describe() const {
  std::string text;
  for (const Part& part : parts_) {
    if (!text.empty()) text += ", ";
    text += part.what + " " + FormatBytes(part.bytes);
  }
  return text;
}

std::string FormatBytes(double bytes) {
  char text[32];
  const double mib = bytes / (1024.0 * 1024.0);
  if (mib >= 1024.0) {
    std::snprintf(text, sizeof(text), "%.1f GiB", mib / 1024.0);
  } else {
    std::snprintf(text, sizeof(text), "%.0f MiB", mib);
  }
  return text;
}

void CheckMemoryEstimate(const std::string& what, const MemoryEstimate& estimate, std::size_t limit_bytes) {
  const std::size_t limit = ResolveMemoryLimit(limit_bytes);
  if (limit == 0 || estimate.total_bytes() <= static_cast<double>(limit)) return;
  const std::string source = limit_bytes != 0 ? "the limit set" : "the machine's available memory";
  throw std::runtime_error(what + " needs about " + FormatBytes(estimate.total_bytes()) + " (" + estimate.Describe() +
                           "), more than the memory limit of " + FormatBytes(static_cast<double>(limit)) + " (" +
                           source + ")");
}

}  // namespace lutex
