#include "colmap_integration/io/colmap_array.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lib/util/binary_io.h"
#include "lib/util/file_streams.h"

namespace lutex {
namespace {

// Reads one "N&" field of the header.
long ReadHeaderField(std::istream& stream, const char* what) {
  std::string digits;
  for (int i = 0; i < 12; ++i) {
    const int c = stream.get();
    if (c == '&') {
      if (digits.empty()) break;
      return std::stol(digits);
    }
    if (c == EOF || c < '0' || c > '9') break;
    digits.push_back(static_cast<char>(c));
  }
  throw std::runtime_error(std::string("not a COLMAP array: bad header field for the ") + what +
                           " (expected WIDTH&HEIGHT&CHANNELS&)");
}

}  // namespace

cv::Mat ReadColmapArray(std::istream& stream) {
  const long width = ReadHeaderField(stream, "width");
  const long height = ReadHeaderField(stream, "height");
  const long channels = ReadHeaderField(stream, "channel count");
  if (width <= 0 || height <= 0 || channels <= 0 || channels > 4 || width > (1 << 20) || height > (1 << 20)) {
    throw std::runtime_error("not a COLMAP array: implausible size " + std::to_string(width) + "x" +
                             std::to_string(height) + "x" + std::to_string(channels));
  }
  const std::size_t plane = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const std::size_t bytes = plane * static_cast<std::size_t>(channels) * sizeof(float);
  if (const std::optional<std::uint64_t> left = BytesLeft(stream); left && *left < bytes) {
    // Before allocating: a corrupt header must not reserve up to 16 TiB (4 x 2^20 x 2^20 floats).
    throw std::runtime_error("truncated COLMAP array: the header promises " + std::to_string(width) + "x" +
                             std::to_string(height) + "x" + std::to_string(channels) + " floats, the file has " +
                             std::to_string(*left / 4));
  }
  std::vector<float> planar(plane * static_cast<std::size_t>(channels));
  stream.read(reinterpret_cast<char*>(planar.data()), static_cast<std::streamsize>(planar.size() * sizeof(float)));
  if (stream.gcount() != static_cast<std::streamsize>(planar.size() * sizeof(float))) {
    throw std::runtime_error("truncated COLMAP array: the header promises " + std::to_string(width) + "x" +
                             std::to_string(height) + "x" + std::to_string(channels) + " floats, the file has " +
                             std::to_string(stream.gcount() / 4));
  }
  cv::Mat array(static_cast<int>(height), static_cast<int>(width), CV_32FC(static_cast<int>(channels)));
  for (std::size_t i = 0; i < plane; ++i) {
    float* pixel = array.ptr<float>() + i * static_cast<std::size_t>(channels);
    for (long c = 0; c < channels; ++c) pixel[c] = planar[static_cast<std::size_t>(c) * plane + i];
  }
  return array;
}

cv::Mat ReadColmapArray(const std::filesystem::path& path) {
  return ParseFile(path, std::ios::binary, [](std::istream& s) { return ReadColmapArray(s); });
}

void WriteColmapArray(const cv::Mat& array, std::ostream& stream) {
  if (array.depth() != CV_32F || array.channels() > 4 || array.empty()) {
    throw std::invalid_argument("COLMAP arrays hold 1 to 4 channels of float32");
  }
  const cv::Mat contiguous = array.isContinuous() ? array : array.clone();
  const int channels = contiguous.channels();
  stream << contiguous.cols << "&" << contiguous.rows << "&" << channels << "&";
  const std::size_t plane = contiguous.total();
  std::vector<float> planar(plane * static_cast<std::size_t>(channels));
  for (std::size_t i = 0; i < plane; ++i) {
    const float* pixel = contiguous.ptr<float>() + i * static_cast<std::size_t>(channels);
    for (int c = 0; c < channels; ++c) planar[static_cast<std::size_t>(c) * plane + i] = pixel[c];
  }
  stream.write(reinterpret_cast<const char*>(planar.data()), static_cast<std::streamsize>(planar.size() * sizeof(float)));
}

void WriteColmapArray(const cv::Mat& array, const std::filesystem::path& path) {
  WriteFileAtomically(path, std::ios::binary, [&](std::ostream& s) { WriteColmapArray(array, s); });
}

cv::Mat ReplaceNanWithZero(const cv::Mat& array) {
  cv::Mat result = array.clone();
  cv::patchNaNs(result, 0.0);
  return result;
}

}  // namespace lutex
