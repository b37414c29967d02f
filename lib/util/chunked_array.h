#pragma once

// An array of a fixed number of value-initialised elements kept in blocks of at most `kChunkBytes`
// instead of one block.
//
// Why: a work buffer of tens of MB taken once per tile (texel fusion's samples) needs one free run of
// that many pages. After the mesh's large vectors are freed and their space is cut up by smaller
// allocations, the allocator often finds no such run and grows the process instead, tile after tile,
// while most of what it holds is free. Blocks of 1 MiB fit into what the earlier work left.
//
// Indexing costs a shift and a mask; the blocks are not contiguous, so there is no `data()`.

#include <cstddef>
#include <memory>
#include <vector>

namespace lutex {

template <typename T>
class ChunkedArray {
 public:
  static constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

  explicit ChunkedArray(std::size_t size) : size_(size) {
    for (std::size_t begin = 0; begin < size; begin += kPerChunk) {
      chunks_.push_back(std::make_unique<T[]>(kPerChunk));
    }
  }

  std::size_t size() const { return size_; }
  std::size_t num_chunks() const { return chunks_.size(); }

  T& operator[](std::size_t i) { return chunks_[i >> kShift][i & (kPerChunk - 1)]; }
  const T& operator[](std::size_t i) const { return chunks_[i >> kShift][i & (kPerChunk - 1)]; }

 private:
  // The largest power of two of elements that fits in kChunkBytes (at least one).
  static constexpr std::size_t ShiftFor(std::size_t bytes) {
    std::size_t shift = 0;
    while ((std::size_t{2} << shift) * sizeof(T) <= bytes) ++shift;
    return shift;
  }
  static constexpr std::size_t kShift = ShiftFor(kChunkBytes);
  static constexpr std::size_t kPerChunk = std::size_t{1} << kShift;

  std::size_t size_ = 0;
  std::vector<std::unique_ptr<T[]>> chunks_;
};

}  // namespace lutex
