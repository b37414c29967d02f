#pragma once

// Images in and out of the linear pipeline. In memory lutex images are CV_32FC3 in RGB order (not
// OpenCV's BGR), linear, nominally in [0, 1]. On disk the encoding is explicit:
//   kSrgb8    8-bit, sRGB transfer function (a camera JPEG/PNG); decoding linearises, encoding applies it
//   kLinear16 16-bit PNG/TIFF whose values / 65535 are linear
//   kFloat    EXR/TIFF float, linear as stored
// Encoding clamps to [0, 1] and rounds to nearest; NaN is written as 0.

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace lutex {

enum class ImageEncoding { kSrgb8, kLinear16, kFloat };

// "srgb8", "linear16", "float"; throws std::invalid_argument otherwise.
ImageEncoding ParseImageEncoding(const std::string& name);
std::string ImageEncodingName(ImageEncoding encoding);

// sRGB transfer functions (IEC 61966-2-1) for one value in [0, 1].
double SrgbToLinear(double encoded);
double LinearToSrgb(double linear);

// Reads an image and returns linear RGB CV_32FC3. Throws std::runtime_error naming the file when it is
// missing or unreadable, or when its bit depth does not match `encoding` (an 8-bit file read as
// kLinear16 is almost always a mistake). Gray images are expanded to RGB.
cv::Mat ReadLinearImage(const std::filesystem::path& path, ImageEncoding encoding);

// The file's samples as stored, checked as ReadLinearImage checks them: a 3-channel BGR picture (gray
// expanded, alpha dropped) of the encoding's depth. DecodeLinearImage of it, or of a window of it, is the linear
// image: a reader that needs only part of a large image linearises only that part.
cv::Mat ReadEncodedPicture(const std::filesystem::path& path, ImageEncoding encoding);

// Encodes linear RGB CV_32FC3 and writes it (temporary name, then rename).
void WriteLinearImage(const cv::Mat& linear_rgb, const std::filesystem::path& path, ImageEncoding encoding);

// Writes an already encoded picture (8-bit or 16-bit, OpenCV's BGR order; format by extension) to a
// temporary name and renames it; throws naming the path when OpenCV cannot write it.
void WriteEncodedImage(const cv::Mat& picture, const std::filesystem::path& path);

// The encoded 8-bit BGR or 16-bit BGR picture that WriteLinearImage would write (for tests and previews).
cv::Mat EncodeLinearImage(const cv::Mat& linear_rgb, ImageEncoding encoding);

// The inverse: linear RGB CV_32FC3 from a 3-channel BGR picture as ReadLinearImage decodes a file's
// samples (the picture's depth must suit `encoding`). Decode(Encode(x)) is x as that encoding stores it.
cv::Mat DecodeLinearImage(const cv::Mat& picture, ImageEncoding encoding);

}  // namespace lutex
