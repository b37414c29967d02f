#pragma once

// What an image file says about itself before its pixels are decoded: size, channels and sample depth,
// read from the header alone (PNG's IHDR chunk, JPEG's start-of-frame marker). A command that writes one
// output per image checks every image this way before its first write, so a wrong-size, wrong-depth or
// not-an-image file in the middle of a dive stops it before anything is written, in a few milliseconds
// per image whatever their size. Other formats (TIFF, EXR, ...) are left to the decoder.

#include <filesystem>
#include <optional>
#include <string>

#include "lib/image/image_io.h"

namespace lutex {

struct ImageHeader {
  std::string format;  // "PNG" or "JPEG"
  int width = 0;
  int height = 0;
  int channels = 0;
  int bits_per_sample = 0;
};

// The header of a PNG or JPEG file (by its signature, not its name); nothing for other formats. Throws
// std::runtime_error naming the file when it is missing, or when it claims to be PNG or JPEG but its
// header is truncated or malformed.
std::optional<ImageHeader> ReadImageHeader(const std::filesystem::path& path);

// Throws std::runtime_error "PATH: the image is WxH but its camera is CWxCH" unless the sizes agree.
void ExpectCameraSize(const std::filesystem::path& path, int width, int height, int camera_width, int camera_height);

// Throws std::runtime_error naming the file unless what its header says suits a `width` x `height` camera
// and `encoding` (8-bit samples for srgb8, 16-bit for linear16; PNG and JPEG hold no float). Files of
// another format pass when a decoder recognises their first bytes (their pixels are checked when decoded);
// a file that no decoder recognises does not.
void CheckImageHeader(const std::filesystem::path& path, int width, int height, ImageEncoding encoding);

}  // namespace lutex
