#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "colmap_integration/io/sparse_model_binary.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/io/sparse_model_text.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_models.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

// Every field of every camera model (ids 0-11) survives binary and text round trips bit for bit.
TEST(SparseModel, BinaryAndTextRoundTripsAreExact) {
  const SparseModel model = testing::MakeTestModel(kNumCameraModels);
  for (SparseFormat format : {SparseFormat::kBinary, SparseFormat::kText}) {
    testing::TempDir dir;
    WriteSparseModel(model, dir.path(), format);
    EXPECT_EQ(DetectSparseFormat(dir.path()), format);
    testing::ExpectModelsEqual(model, ReadSparseModel(dir.path()));
  }
}

TEST(SparseModel, StreamReadersParseWhatStreamWritersWrite) {
  const SparseModel model = testing::MakeTestModel(3);
  std::stringstream cameras, images;
  WriteCamerasText(model.cameras, cameras);
  WriteImagesBinary(model.images, images);
  SparseModel read;
  read.cameras = ReadCamerasText(cameras);
  read.images = ReadImagesBinary(images);
  read.points3D = model.points3D;
  testing::ExpectModelsEqual(model, read);
}

// COLMAP writes an empty line for images without 2-D points; comments and CRLF line ends are fine.
TEST(SparseModel, TextReaderAcceptsEmptyPointLinesCommentsAndCrlf) {
  std::istringstream images(
      "# Image list\r\n1 1 0 0 0 0.1 0.2 0.3 1 a.png\r\n\r\n# comment\n2 1 0 0 0 0 0 1 1 b.png\n10.5 20.5 -1\n");
  const auto read = ReadImagesText(images);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_TRUE(read.at(1).points2D.empty());
  EXPECT_EQ(read.at(1).name, "a.png");
  ASSERT_EQ(read.at(2).points2D.size(), 1u);
  EXPECT_EQ(read.at(2).points2D[0].point3D_id, kInvalidPoint3DId);
}

std::string ErrorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "";
}

TEST(SparseModel, MissingOrTruncatedImagesBinIsAnErrorNamingTheFile) {
  testing::TempDir dir;
  WriteSparseModel(testing::MakeTestModel(2), dir.path(), SparseFormat::kBinary);
  const fs::path images = dir.path() / "images.bin";
  fs::resize_file(images, fs::file_size(images) - 7);
  std::string message = ErrorOf([&] { ReadSparseModel(dir.path()); });
  EXPECT_NE(message.find(images.string()), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  fs::remove(images);
  message = ErrorOf([&] { ReadSparseModel(dir.path()); });
  EXPECT_NE(message.find("images.bin: no such file"), std::string::npos) << message;
}

TEST(SparseModel, ImageNamingAnUndefinedCameraIsAnError) {
  SparseModel model = testing::MakeTestModel(2);
  testing::TempDir dir;
  WriteSparseModel(model, dir.path(), SparseFormat::kText);
  std::ofstream(dir.path() / "cameras.txt") << "1 SIMPLE_PINHOLE 640 480 500 320 240\n";
  const std::string message = ErrorOf([&] { ReadSparseModel(dir.path()); });
  EXPECT_NE(message.find("images.txt"), std::string::npos) << message;
  EXPECT_NE(message.find("names camera 2"), std::string::npos) << message;
}

TEST(SparseModel, ParameterCountMismatchIsAnErrorWithTheLine) {
  testing::TempDir dir;
  std::ofstream(dir.path() / "cameras.txt") << "# header\n1 OPENCV 640 480 500 500 320 240 0.1\n";
  const std::string message = ErrorOf([&] { ReadCamerasText(dir.path() / "cameras.txt"); });
  EXPECT_NE(message.find("cameras.txt: line 2"), std::string::npos) << message;
  EXPECT_NE(message.find("takes 8 parameters"), std::string::npos) << message;
}

TEST(SparseModel, UnknownModelIdInBinaryIsNamed) {
  std::stringstream stream;
  const std::uint64_t count = 1;
  const std::uint32_t camera_id = 5;
  const std::int32_t model_id = 99;
  stream.write(reinterpret_cast<const char*>(&count), 8);
  stream.write(reinterpret_cast<const char*>(&camera_id), 4);
  stream.write(reinterpret_cast<const char*>(&model_id), 4);
  const std::string message = ErrorOf([&] { ReadCamerasBinary(stream); });
  EXPECT_NE(message.find("camera 5 has unknown camera model id 99"), std::string::npos) << message;
}

TEST(SparseModel, NanPoseIsAnError) {
  SparseModel model = testing::MakeTestModel(1);
  testing::TempDir dir;
  WriteSparseModel(model, dir.path(), SparseFormat::kBinary);
  model.images.begin()->second.cam_from_world.translation.y() = std::nan("");
  std::ofstream images(dir.path() / "images.bin", std::ios::binary);
  WriteImagesBinary(model.images, images);
  images.close();
  const std::string message = ErrorOf([&] { ReadSparseModel(dir.path()); });
  EXPECT_NE(message.find("images.bin: image 1"), std::string::npos) << message;
  EXPECT_NE(message.find("not finite"), std::string::npos) << message;
}

// COLMAP >= 3.12 adds rigs and frames files; lutex reads poses from images and ignores them.
TEST(SparseModel, RigsAndFramesFilesAreTolerated) {
  const SparseModel model = testing::MakeTestModel(2);
  testing::TempDir dir;
  WriteSparseModel(model, dir.path(), SparseFormat::kBinary);
  std::ofstream(dir.path() / "rigs.bin") << "whatever a newer COLMAP writes";
  std::ofstream(dir.path() / "frames.bin") << "whatever a newer COLMAP writes";
  testing::ExpectModelsEqual(model, ReadSparseModel(dir.path()));
}

}  // namespace
}  // namespace lutex
