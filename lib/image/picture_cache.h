#pragma once

// Decoded pictures kept for reading again. A tiled bake reads a view once per tile that it sees, and
// neighbouring tiles see mostly the same views: decoding a 12 MP PNG costs about a second of one core,
// holding it (8-bit) 36 MB. The cache keeps the most recently used pictures within a byte budget and
// drops the least recently used first, so memory stays bounded by the budget, not by the dive.

#include <cstddef>
#include <functional>
#include <list>
#include <mutex>
#include <unordered_map>
#include <utility>

#include <opencv2/core.hpp>

namespace lutex {

class PictureCache {
 public:
  // 0 holds nothing (every Get decodes).
  explicit PictureCache(std::size_t capacity_bytes) : capacity_bytes_(capacity_bytes) {}
  PictureCache(const PictureCache&) = delete;
  PictureCache& operator=(const PictureCache&) = delete;

  // The picture under `key`: the held one, or `decode()` (run without the lock, so threads decode
  // different pictures at once), kept when it fits the budget. The pixels are shared with the cache:
  // callers must not write to them. Exceptions from `decode` pass through and nothing is kept.
  cv::Mat Get(std::size_t key, const std::function<cv::Mat()>& decode);

  // Whether `key` is held now (a Get would not decode).
  bool Holds(std::size_t key) const;

  std::size_t held_bytes() const;
  std::size_t capacity_bytes() const { return capacity_bytes_; }
  // How many Gets decoded (the others were served from the cache).
  std::size_t decodes() const;

 private:
  using Entry = std::pair<std::size_t, cv::Mat>;  // key, picture; most recently used first

  const std::size_t capacity_bytes_;
  mutable std::mutex mutex_;
  std::list<Entry> entries_;
  std::unordered_map<std::size_t, std::list<Entry>::iterator> by_key_;
  std::size_t held_bytes_ = 0;
  std::size_t decodes_ = 0;
};

}  // namespace lutex
