#include "lib/image/picture_cache.h"

namespace lutex {

namespace {

std::size_t PictureBytes(const cv::Mat& picture) { return picture.total() * picture.elemSize(); }

}  // namespace

cv::Mat PictureCache::Get(std::size_t key, const std::function<cv::Mat()>& decode) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto found = by_key_.find(key);
    if (found != by_key_.end()) {
      entries_.splice(entries_.begin(), entries_, found->second);
      return found->second->second;
    }
    ++decodes_;
  }
  cv::Mat picture = decode();
  const std::size_t bytes = PictureBytes(picture);
  if (bytes == 0 || bytes > capacity_bytes_) return picture;
  std::lock_guard<std::mutex> lock(mutex_);
  if (by_key_.count(key) != 0) return picture;  // another thread decoded it meanwhile
  while (held_bytes_ + bytes > capacity_bytes_) {
    held_bytes_ -= PictureBytes(entries_.back().second);
    by_key_.erase(entries_.back().first);
    entries_.pop_back();
  }
  entries_.emplace_front(key, picture);
  by_key_[key] = entries_.begin();
  held_bytes_ += bytes;
  return picture;
}

bool PictureCache::Holds(std::size_t key) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return by_key_.count(key) != 0;
}

std::size_t PictureCache::decodes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return decodes_;
}

std::size_t PictureCache::held_bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return held_bytes_;
}

}  // namespace lutex
