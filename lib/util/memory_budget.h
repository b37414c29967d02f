#pragma once

// How much memory a stage may take, and the check that refuses, before anything large is allocated, a stage
// whose estimate exceeds it. A dive of 10,000 images must not be swapped to death or killed by the kernel
// without a word: a camera of 20000 x 20000 pixels, or a corrupt size field, is refused with the estimate
// and the limit in one line instead.
//
// Estimates are sums of named parts, each a count times the bytes one item takes (per pixel of an image a
// worker holds, per face of the mesh, ...), so the refusal says where the memory would go.

#include <cstddef>
#include <string>
#include <vector>

namespace lutex {

// What this process can have without swapping: MemAvailable of /proc/meminfo plus AllocatorFreeBytes()
// (what an earlier stage freed and the allocator keeps for this process); 0 when MemAvailable is unknown.
std::size_t AvailableMemoryBytes();

// The free memory this process's allocator holds mapped, to hand out again: tcmalloc's page heap's free
// bytes (`lutex` is linked with tcmalloc: cmake/allocator.cmake), looked up through a weak symbol so the
// libraries do not depend on it; 0 under glibc's malloc, which returns large blocks to the system.
std::size_t AllocatorFreeBytes();

// The limit a stage is held to: `limit_bytes`, or when it is 0, the machine's available memory (0 when
// neither is known: no limit).
std::size_t ResolveMemoryLimit(std::size_t limit_bytes);

class MemoryEstimate {
 public:
  // Adds `count` items of `bytes_each`, described as `what` ("2 workers' image buffers").
  void Add(const std::string& what, double count, double bytes_each);
  double total_bytes() const { return total_bytes_; }
  // "2 workers' image buffers 1.6 GiB, the mesh and its ray-casting index 0.2 GiB".
  std::string Describe() const;

 private:
  struct Part {
    std::string what;
    double bytes;
  };
  std::vector<Part> parts_;
  double total_bytes_ = 0.0;
};

// Throws std::runtime_error "`what` needs about 31.4 GiB (parts), more than the memory limit of 22.0 GiB
// (the machine's available memory)" when the estimate exceeds the resolved
// limit. `limit_bytes` as for ResolveMemoryLimit.
void CheckMemoryEstimate(const std::string& what, const MemoryEstimate& estimate, std::size_t limit_bytes);

// "1.6 GiB", "340 MiB".
std::string FormatBytes(double bytes);

}  // namespace lutex
