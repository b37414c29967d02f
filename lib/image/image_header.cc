#include "lib/image/image_header.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>

namespace lutex {
namespace {

std::uint32_t BigEndian(const unsigned char* bytes, int count) {
  std::uint32_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

std::runtime_error Malformed(const std::filesystem::path& path, const std::string& format, const std::string& what) {
  return std::runtime_error(path.string() + ": not a readable " + format + " image (" + what + ")");
}

ImageHeader ReadPngHeader(std::istream& file, const std::filesystem::path& path) {
  // Signature (8), IHDR length (4) and type (4), width, height (4 each), bit depth, colour type.
  std::array<unsigned char, 26> bytes{};
  if (!file.read(reinterpret_cast<char*>(bytes.data()), bytes.size())) throw Malformed(path, "PNG", "truncated header");
  if (std::string(reinterpret_cast<const char*>(&bytes[12]), 4) != "IHDR") {
    throw Malformed(path, "PNG", "no IHDR chunk first");
  }
  ImageHeader header;
  header.format = "PNG";
  header.width = static_cast<int>(BigEndian(&bytes[16], 4));
  header.height = static_cast<int>(BigEndian(&bytes[20], 4));
  header.bits_per_sample = bytes[24];
  switch (bytes[25]) {
    case 0: header.channels = 1; break;
    case 2: header.channels = 3; break;
    case 3: header.channels = 3, header.bits_per_sample = 8; break;  // palette: 8-bit RGB samples
    case 4: header.channels = 2; break;
    case 6: header.channels = 4; break;
    default: throw Malformed(path, "PNG", "unknown colour type " + std::to_string(bytes[25]));
  }
  return header;
}

ImageHeader ReadJpegHeader(std::istream& file, const std::filesystem::path& path) {
  file.seekg(2);
  for (;;) {
    std::array<unsigned char, 4> marker{};
    if (!file.read(reinterpret_cast<char*>(marker.data()), 4)) throw Malformed(path, "JPEG", "no frame header");
    if (marker[0] != 0xFF) throw Malformed(path, "JPEG", "broken marker");
    const int type = marker[1];
    const int length = static_cast<int>(BigEndian(&marker[2], 2));
    if (length < 2) throw Malformed(path, "JPEG", "broken marker length");
    const bool start_of_frame = type >= 0xC0 && type <= 0xCF && type != 0xC4 && type != 0xC8 && type != 0xCC;
    if (type == 0xDA) throw Malformed(path, "JPEG", "image data before a frame header");
    if (!start_of_frame) {
      file.seekg(length - 2, std::ios::cur);
      continue;
    }
    std::array<unsigned char, 6> frame{};
    if (!file.read(reinterpret_cast<char*>(frame.data()), frame.size())) throw Malformed(path, "JPEG", "truncated frame header");
    ImageHeader header;
    header.format = "JPEG";
    header.bits_per_sample = frame[0];
    header.height = static_cast<int>(BigEndian(&frame[1], 2));
    header.width = static_cast<int>(BigEndian(&frame[3], 2));
    header.channels = frame[5];
    return header;
  }
}

}  // namespace

std::optional<ImageHeader> ReadImageHeader(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(path.string() + ": no such image");
  std::array<unsigned char, 8> signature{};
  file.read(reinterpret_cast<char*>(signature.data()), signature.size());
  const std::size_t got = static_cast<std::size_t>(file.gcount());
  file.clear();
  file.seekg(0);
  static constexpr std::array<unsigned char, 8> kPng = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (got == 8 && signature == kPng) return ReadPngHeader(file, path);
  if (got >= 3 && signature[0] == 0xFF && signature[1] == 0xD8 && signature[2] == 0xFF) return ReadJpegHeader(file, path);
  return std::nullopt;
}

void ExpectCameraSize(const std::filesystem::path& path, int width, int height, int camera_width, int camera_height) {
  if (width == camera_width && height == camera_height) return;
  throw std::runtime_error(path.string() + ": the image is " + std::to_string(width) + "x" + std::to_string(height) +
                           " but its camera is " + std::to_string(camera_width) + "x" + std::to_string(camera_height));
}

void CheckImageHeader(const std::filesystem::path& path, int width, int height, ImageEncoding encoding) {
  const std::optional<ImageHeader> header = ReadImageHeader(path);
  if (!header) {
    // Another format (TIFF, EXR, ...): its pixels are checked when decoded, but a file that no decoder
    // recognises by its first bytes is refused now, before anything is written.
    if (!cv::haveImageReader(path.string())) {
      throw std::runtime_error(path.string() + ": not an image (its first bytes match no image format lutex reads)");
    }
    return;
  }
  ExpectCameraSize(path, header->width, header->height, width, height);
  if (header->channels != 1 && header->channels != 3 && header->channels != 4) {
    throw std::runtime_error(path.string() + ": the image has " + std::to_string(header->channels) +
                             " channels; lutex reads grey, RGB or RGBA");
  }
  const int wanted = encoding == ImageEncoding::kSrgb8 ? 8 : encoding == ImageEncoding::kLinear16 ? 16 : 0;
  if (header->bits_per_sample != wanted) {
    throw std::runtime_error(path.string() + ": the image has " + std::to_string(header->bits_per_sample) +
                             "-bit samples but the encoding is " + ImageEncodingName(encoding));
  }
}

}  // namespace lutex
