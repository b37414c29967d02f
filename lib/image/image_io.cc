#include "lib/image/image_io.h"

#include <algorithm>
#include <cmath>
#include <vector>
#include <cstdlib>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lib/util/file_streams.h"

namespace lutex {
namespace {

// A 256-entry decoding table for 8-bit sRGB.
const float* SrgbDecodeTable() {
  static const auto table = [] {
    static float values[256];
    for (int i = 0; i < 256; ++i) values[i] = static_cast<float>(SrgbToLinear(i / 255.0));
    return values;
  }();
  return table;
}

// Encoding linear values to 8-bit sRGB exactly without a pow per value: code k is the largest k whose
// threshold SrgbToLinear((k - 0.5) / 255) the value reaches (the rounding points of the encoding).
const std::vector<double>& SrgbEncodeThresholds() {
  static const std::vector<double> thresholds = [] {
    std::vector<double> values;
    for (int k = 1; k < 256; ++k) values.push_back(SrgbToLinear((k - 0.5) / 255.0));
    return values;
  }();
  return thresholds;
}

// A first guess from a 2^14-entry table, corrected against the exact thresholds (at most a step or two).
uchar EncodeSrgb8(float linear) {
  static const std::vector<uchar> guess = [] {
    std::vector<uchar> table(16385);
    const std::vector<double>& thresholds = SrgbEncodeThresholds();
    for (int i = 0; i <= 16384; ++i) {
      table[i] = static_cast<uchar>(std::upper_bound(thresholds.begin(), thresholds.end(), i / 16384.0) -
                                     thresholds.begin());
    }
    return table;
  }();
  const std::vector<double>& thresholds = SrgbEncodeThresholds();
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  const double value = linear;
  int code = guess[static_cast<int>(value * 16384.0)];
  while (code < 255 && value >= thresholds[code]) ++code;
  while (code > 0 && value < thresholds[code - 1]) --code;
  return static_cast<uchar>(code);
}

}  // namespace

ImageEncoding ParseImageEncoding(const std::string& name) {
  if (name == "srgb8") return ImageEncoding::kSrgb8;
  if (name == "linear16") return ImageEncoding::kLinear16;
  if (name == "float") return ImageEncoding::kFloat;
  throw std::invalid_argument("unknown image encoding '" + name + "' (expected srgb8, linear16 or float)");
}

std::string ImageEncodingName(ImageEncoding encoding) {
  switch (encoding) {
    case ImageEncoding::kSrgb8: return "srgb8";
    case ImageEncoding::kLinear16: return "linear16";
    case ImageEncoding::kFloat: return "float";
  }
  return "?";
}

double SrgbToLinear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

double LinearToSrgb(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

cv::Mat ReadLinearImage(const std::filesystem::path& path, ImageEncoding encoding) {
  return DecodeLinearImage(ReadEncodedPicture(path, encoding), encoding);
}

cv::Mat ReadEncodedPicture(const std::filesystem::path& path, ImageEncoding encoding) {
  // OpenCV reads EXR only when asked to by this variable, which must be set before the first read.
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);
  if (!std::filesystem::exists(path)) throw std::runtime_error(path.string() + ": no such image");
  cv::Mat stored = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (stored.empty()) throw std::runtime_error(path.string() + ": not a readable image (corrupt, truncated or unknown format)");
  if (stored.channels() == 1) cv::cvtColor(stored, stored, cv::COLOR_GRAY2BGR);
  if (stored.channels() == 4) cv::cvtColor(stored, stored, cv::COLOR_BGRA2BGR);
  const int depth = stored.depth();
  const bool matches = (encoding == ImageEncoding::kSrgb8 && depth == CV_8U) ||
                       (encoding == ImageEncoding::kLinear16 && depth == CV_16U) ||
                       (encoding == ImageEncoding::kFloat && (depth == CV_32F || depth == CV_16F));
  if (!matches) {
    throw std::runtime_error(path.string() + ": the image has " +
                             (depth == CV_8U ? "8-bit" : depth == CV_16U ? "16-bit" : "float") +
                             " samples but the encoding is " + ImageEncodingName(encoding));
  }
  return stored;
}

cv::Mat DecodeLinearImage(const cv::Mat& picture, ImageEncoding encoding) {
  CV_Assert(picture.channels() == 3);
  cv::Mat linear(picture.size(), CV_32FC3);
  if (encoding == ImageEncoding::kSrgb8) {
    CV_Assert(picture.depth() == CV_8U);
    const float* table = SrgbDecodeTable();
    for (int row = 0; row < picture.rows; ++row) {
      const auto* in = picture.ptr<cv::Vec3b>(row);
      auto* out = linear.ptr<cv::Vec3f>(row);
      for (int col = 0; col < picture.cols; ++col) out[col] = cv::Vec3f(table[in[col][2]], table[in[col][1]], table[in[col][0]]);
    }
    return linear;
  }
  cv::Mat as_float;
  picture.convertTo(as_float, CV_32FC3, encoding == ImageEncoding::kLinear16 ? 1.0 / 65535.0 : 1.0);
  cv::cvtColor(as_float, linear, cv::COLOR_BGR2RGB);
  return linear;
}

namespace {

// RGB float to BGR of type Out in one pass, each value through `encode` (which must map NaN to 0): no
// intermediate image (at 12 MP a float copy is 144 MB of fresh memory per image).
template <typename Out, typename Encode>
cv::Mat EncodeToBgr(const cv::Mat& linear_rgb, int type, Encode encode) {
  cv::Mat encoded(linear_rgb.size(), type);
  for (int row = 0; row < linear_rgb.rows; ++row) {
    const auto* in = linear_rgb.ptr<cv::Vec3f>(row);
    auto* out = encoded.ptr<cv::Vec<Out, 3>>(row);
    for (int col = 0; col < linear_rgb.cols; ++col) {
      out[col] = cv::Vec<Out, 3>(encode(in[col][2]), encode(in[col][1]), encode(in[col][0]));
    }
  }
  return encoded;
}

}  // namespace

cv::Mat EncodeLinearImage(const cv::Mat& linear_rgb, ImageEncoding encoding) {
  CV_Assert(linear_rgb.type() == CV_32FC3);
  switch (encoding) {
    case ImageEncoding::kFloat:
      return EncodeToBgr<float>(linear_rgb, CV_32FC3, [](float value) { return std::isnan(value) ? 0.0f : value; });
    case ImageEncoding::kLinear16:
      return EncodeToBgr<ushort>(linear_rgb, CV_16UC3, [](float value) {  // saturating and rounding
        return std::isnan(value) ? ushort{0} : cv::saturate_cast<ushort>(value * 65535.0f);
      });
    case ImageEncoding::kSrgb8:
      break;
  }
  return EncodeToBgr<uchar>(linear_rgb, CV_8UC3, EncodeSrgb8);
}

void WriteEncodedImage(const cv::Mat& picture, const std::filesystem::path& path) {
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);
  // Encoded in memory, then written by lutex: a failure to write (a full disk) is named as such, and the
  // codec libraries never see the file, so none of their own lines reach the user.
  std::vector<uchar> bytes;
  bool encoded = false;
  try {
    encoded = cv::imencode(path.extension().string(), picture, bytes);
  } catch (const cv::Exception&) {
    encoded = false;
  }
  if (!encoded) {
    throw std::runtime_error(path.string() + ": cannot encode a " + std::to_string(picture.channels()) + "-channel " +
                             (picture.depth() == CV_8U ? "8-bit" : picture.depth() == CV_16U ? "16-bit" : "float") +
                             " image as " + path.extension().string());
  }
  WriteBytesAtomically(path, bytes.data(), bytes.size());
}

void WriteLinearImage(const cv::Mat& linear_rgb, const std::filesystem::path& path, ImageEncoding encoding) {
  WriteEncodedImage(EncodeLinearImage(linear_rgb, encoding), path);
}

}  // namespace lutex
