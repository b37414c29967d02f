#include "lib/lut/frustum_lut.h"

#include <cmath>
#include <cstring>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "lib/lut/lut_file.h"
#include "lib/lut/lut_slab_images.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

FrustumLutGrid Grid(int nx, int ny, int nz, DepthSpacing spacing) {
  FrustumLutGrid grid;
  grid.nx = nx;
  grid.ny = ny;
  grid.nz = nz;
  grid.z_near = 0.5;
  grid.z_far = 3.0;
  grid.spacing = spacing;
  grid.image_width = 640;
  grid.image_height = 480;
  return grid;
}

// Linear in the coordinates the LUT interpolates linearly in: pixel u, v and z (or 1/z).
LutNode LinearFunction(double u, double v, double z, DepthSpacing spacing) {
  const double w = spacing == DepthSpacing::kUniformZ ? z : 1.0 / z;
  LutNode node;
  node.alpha = Eigen::Vector3d(0.3 + 0.001 * u - 0.002 * v + 0.5 * w, 0.1 + 0.0005 * u, 2.0 - w);
  node.beta = Eigen::Vector3d(0.01 * w, 0.002 * v, 0.0001 * u + 0.0003 * v + 0.02 * w);
  return node;
}

FrustumLut FilledLinear(const FrustumLutGrid& grid) {
  FrustumLut lut(grid);
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.NodesY(); ++j) {
      for (int i = 0; i < grid.NodesX(); ++i) {
        const Eigen::Vector2d pixel = lut.NodePixel(i, j);
        lut.node(i, j, k) = LinearFunction(pixel.x(), pixel.y(), grid.SlabDepth(k), grid.spacing);
      }
    }
  }
  return lut;
}

// The same made non-negative, as every LUT file holds (calibration bounds alpha and beta below by 0).
FrustumLut FilledNonNegative(const FrustumLutGrid& grid) {
  FrustumLut lut = FilledLinear(grid);
  for (int n = 0; n < grid.NumNodes(); ++n) {
    lut.node(n).alpha = lut.node(n).alpha.cwiseAbs();
    lut.node(n).beta = lut.node(n).beta.cwiseAbs();
  }
  return lut;
}

// A LUT filled from a function linear in (u, v, z) (uniform z) or (u, v, 1/z) (uniform 1/z) reproduces it
// exactly anywhere inside the frustum, because trilinear interpolation is exact on linear functions.
TEST(FrustumLut, ReproducesLinearFunctionsAnywhere) {
  std::mt19937 random(7);
  for (DepthSpacing spacing : {DepthSpacing::kUniformZ, DepthSpacing::kUniformInverseZ}) {
    FrustumLutGrid grid = Grid(8, 6, 5, spacing);
    grid.alpha_interpolation = AlphaInterpolation::kTrilinear;
    const FrustumLut lut = FilledLinear(grid);
    std::uniform_real_distribution<double> u(0, 640), v(0, 480), z(0.5, 3.0);
    for (int n = 0; n < 500; ++n) {
      const double pu = u(random), pv = v(random), pz = z(random);
      const LutNode expected = LinearFunction(pu, pv, pz, spacing);
      const LutNode actual = lut.Lookup(pu, pv, pz);
      ASSERT_LT((actual.alpha - expected.alpha).norm(), 1e-12);
      ASSERT_LT((actual.beta - expected.beta).norm(), 1e-12);
    }
  }
}

// With inverse-square alpha interpolation, alpha = L(u, v, 1/z) / z^2 is reproduced exactly (L linear),
// which is what makes 10 slabs enough for light that falls off with the square of the distance.
TEST(FrustumLut, InverseSquareAlphaReproducesLinearOverZSquared) {
  const FrustumLut lut = [] {
    FrustumLut filled = FilledLinear(Grid(8, 6, 5, DepthSpacing::kUniformInverseZ));
    for (int k = 0; k < filled.grid().nz; ++k) {
      const double z = filled.grid().SlabDepth(k);
      for (int j = 0; j < filled.grid().NodesY(); ++j) {
        for (int i = 0; i < filled.grid().NodesX(); ++i) filled.node(i, j, k).alpha /= z * z;
      }
    }
    return filled;
  }();
  std::mt19937 random(9);
  std::uniform_real_distribution<double> u(0, 640), v(0, 480), z(0.5, 3.0);
  for (int n = 0; n < 500; ++n) {
    const double pu = u(random), pv = v(random), pz = z(random);
    const LutNode expected = LinearFunction(pu, pv, pz, DepthSpacing::kUniformInverseZ);
    const LutNode actual = lut.Lookup(pu, pv, pz);
    ASSERT_LT((actual.alpha - expected.alpha / (pz * pz)).norm(), 1e-12);
    ASSERT_LT((actual.beta - expected.beta).norm(), 1e-12);
  }
}

// Lookup (direct, for restoration) and Weights (for calibration) are the same interpolation.
TEST(FrustumLut, LookupEqualsTheWeightedSumOfNodes) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> value(0.0, 1.0), u(-20, 660), v(-20, 500), z(0.3, 3.5);
  for (AlphaInterpolation interpolation : {AlphaInterpolation::kTrilinear, AlphaInterpolation::kInverseSquare}) {
    FrustumLutGrid grid = Grid(5, 4, 6, DepthSpacing::kUniformInverseZ);
    grid.alpha_interpolation = interpolation;
    FrustumLut lut(grid);
    for (int n = 0; n < grid.NumNodes(); ++n) {
      lut.node(n).alpha = Eigen::Vector3d(value(random), value(random), value(random));
      lut.node(n).beta = Eigen::Vector3d(value(random), value(random), value(random));
    }
    for (int trial = 0; trial < 300; ++trial) {
      const double pu = u(random), pv = v(random), pz = z(random);
      const NodeWeights weights = lut.Weights(pu, pv, pz);
      LutNode summed;
      for (int n = 0; n < weights.count; ++n) {
        summed.alpha += weights.alpha_weight[n] * lut.node(weights.node[n]).alpha;
        summed.beta += weights.weight[n] * lut.node(weights.node[n]).beta;
      }
      const LutNode looked_up = lut.Lookup(pu, pv, pz);
      ASSERT_LT((looked_up.alpha - summed.alpha).norm(), 1e-12);
      ASSERT_LT((looked_up.beta - summed.beta).norm(), 1e-12);
    }
  }
}

// Outside the image or the depth range the border value holds.
TEST(FrustumLut, ClampsAtTheBorders) {
  const FrustumLut lut = FilledLinear(Grid(4, 3, 3, DepthSpacing::kUniformZ));
  EXPECT_LT((lut.Lookup(-50, 100, 9.0).alpha - lut.Lookup(0, 100, 3.0).alpha).norm(), 1e-12);
  EXPECT_LT((lut.Lookup(700, 500, 0.1).beta - lut.Lookup(640, 480, 0.5).beta).norm(), 1e-12);
}

TEST(FrustumLut, WeightsSumToOneAndNameTheRightNodes) {
  const FrustumLut lut = FilledLinear(Grid(4, 3, 3, DepthSpacing::kUniformInverseZ));
  const NodeWeights at_node = lut.Weights(160, 160, lut.grid().SlabDepth(1));  // node (1, 1, 1) exactly
  double weight_of_node = 0.0;
  for (int n = 0; n < at_node.count; ++n) {
    if (at_node.node[n] == lut.grid().NodeIndex(1, 1, 1)) weight_of_node += at_node.weight[n];
  }
  EXPECT_NEAR(weight_of_node, 1.0, 1e-12);
  const NodeWeights inside = lut.Weights(200.0, 100.0, 1.3);
  double sum = 0;
  for (int n = 0; n < inside.count; ++n) sum += inside.weight[n];
  EXPECT_EQ(inside.count, 8);
  EXPECT_NEAR(sum, 1.0, 1e-15);
}

// Coarse to fine and back: corner-aligned grids nest (every 4 x 3 node is a 20 x 15 node), so upsampling
// then downsampling returns the coarse nodes exactly, for any values.
TEST(FrustumLut, ResampleUpThenDownIsIdentityOnCoarseNodes) {
  FrustumLut coarse(Grid(4, 3, 10, DepthSpacing::kUniformInverseZ));
  std::mt19937 random(3);
  std::uniform_real_distribution<double> value(0.0, 1.0);
  for (int n = 0; n < coarse.grid().NumNodes(); ++n) {
    coarse.node(n).alpha = Eigen::Vector3d(value(random), value(random), value(random));
    coarse.node(n).beta = Eigen::Vector3d(value(random), value(random), value(random));
  }
  const FrustumLut back = coarse.Resampled(Grid(20, 15, 10, DepthSpacing::kUniformInverseZ))
                              .Resampled(Grid(40, 30, 10, DepthSpacing::kUniformInverseZ))
                              .Resampled(coarse.grid());
  for (int n = 0; n < coarse.grid().NumNodes(); ++n) {
    ASSERT_LT((back.node(n).alpha - coarse.node(n).alpha).norm(), 1e-12);
    ASSERT_LT((back.node(n).beta - coarse.node(n).beta).norm(), 1e-12);
  }
}

TEST(LutFile, RoundTripIsExact) {
  const FrustumLut lut = FilledNonNegative(Grid(5, 4, 3, DepthSpacing::kUniformInverseZ));
  testing::TempDir dir;
  WriteLut(lut, dir.path() / "a.lut");
  const FrustumLut read = ReadLut(dir.path() / "a.lut");
  EXPECT_TRUE(read.grid() == lut.grid());
  for (int n = 0; n < lut.grid().NumNodes(); ++n) {
    ASSERT_EQ(read.node(n).alpha, lut.node(n).alpha);
    ASSERT_EQ(read.node(n).beta, lut.node(n).beta);
  }
}

// A LUT shaded with a light rig is written as version 2 and read back with the same rig.
TEST(LutFile, RoundTripKeepsTheShadingRig) {
  FrustumLutGrid grid = Grid(3, 2, 2, DepthSpacing::kUniformZ);
  for (const double x : {-0.4, 0.4}) {
    Light light;
    light.position_in_cam = Eigen::Vector3d(x, 0.01, 0);
    light.direction_in_cam = Eigen::Vector3d(0.1, 0, 1).normalized();
    light.intensity = Eigen::Vector3d(1.2, 1.0, 0.9);
    light.profile = BeamProfile::kCyclesSpot;
    light.spot_size_rad = 1.9;
    light.spot_blend = 0.4;
    grid.shading.rig.lights.push_back(light);
  }
  const FrustumLut lut = FilledNonNegative(grid);
  std::ostringstream written;
  WriteLut(lut, written);
  EXPECT_EQ(written.str().rfind("LUTEX-LUT 2\n", 0), 0u);
  std::istringstream stream(written.str());
  const FrustumLut read = ReadLut(stream);
  EXPECT_TRUE(read.grid() == lut.grid());
  EXPECT_FALSE(read.grid() == Grid(3, 2, 2, DepthSpacing::kUniformZ));
}

// A LUT fitted to images without their forward scattering is written as version 3 and read back with it;
// a negative scattering coefficient in a header is a clear error.
TEST(LutFile, RoundTripKeepsTheForwardScattering) {
  FrustumLutGrid grid = Grid(3, 2, 2, DepthSpacing::kUniformZ);
  grid.forward_scatter.scattering = Eigen::Vector3d(0.35, 0.4, 0.42);
  grid.forward_scatter.anisotropy_g = 0.85;
  std::ostringstream written;
  WriteLut(FilledNonNegative(grid), written);
  EXPECT_EQ(written.str().rfind("LUTEX-LUT 3\n", 0), 0u);
  std::istringstream stream(written.str());
  EXPECT_TRUE(ReadLut(stream).grid() == grid);
  grid.forward_scatter.anisotropy_g = 0.9;
  std::istringstream again(written.str());
  EXPECT_FALSE(ReadLut(again).grid() == grid);

  std::string negative = written.str();
  const std::size_t at = negative.find("0.35");
  ASSERT_NE(at, std::string::npos);
  negative.replace(at, 4, "-0.3");
  std::istringstream bad(negative);
  EXPECT_THROW(
      {
        try {
          ReadLut(bad);
        } catch (const std::runtime_error& error) {
          EXPECT_NE(std::string(error.what()).find("scattering coefficients must be finite and >= 0"), std::string::npos)
              << error.what();
          throw;
        }
      },
      std::runtime_error);
}

std::string ReadError(const std::string& bytes) {
  std::istringstream stream(bytes);
  try {
    ReadLut(stream);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

TEST(LutFile, BadFilesAreClearErrors) {
  std::ostringstream good;
  WriteLut(FilledNonNegative(Grid(2, 2, 2, DepthSpacing::kUniformZ)), good);
  const std::string bytes = good.str();
  EXPECT_NE(ReadError(bytes.substr(0, bytes.size() - 5)).find("truncated"), std::string::npos);
  EXPECT_NE(ReadError("hello").find("not a lutex LUT"), std::string::npos);
  EXPECT_NE(ReadError("LUTEX-LUT 4\n{}\n").find("version"), std::string::npos);
  EXPECT_NE(ReadError("LUTEX-LUT 1\n{\"nx\": 2}\n").find("lacks a field"), std::string::npos);
  EXPECT_NE(ReadError(bytes + "x").find("after its values"), std::string::npos);
  std::string with_nan = bytes;
  const double nan = std::nan("");
  std::memcpy(&with_nan[with_nan.size() - 8], &nan, 8);
  EXPECT_NE(ReadError(with_nan).find("not finite"), std::string::npos);
  // The last node's alpha (red), then its beta (blue), made negative: calibration never writes those.
  for (const std::size_t from_end : {std::size_t{48}, std::size_t{8}}) {
    std::string negative = bytes;
    const double value = -0.25;
    std::memcpy(&negative[negative.size() - from_end], &value, 8);
    EXPECT_NE(ReadError(negative).find("negative alpha or beta: the file is corrupt"), std::string::npos) << from_end;
  }
}

// Found reviewing the reader for fuzz/lut_fuzzer: a header's grid is checked against the int node count and the
// file's size before the nodes are allocated, so a corrupt header can neither overflow nor reserve gigabytes.
TEST(LutFile, AHeaderPromisingMoreThanTheFileHoldsIsAnError) {
  std::ostringstream good;
  WriteLut(FilledNonNegative(Grid(2, 2, 2, DepthSpacing::kUniformZ)), good);
  const std::string bytes = good.str();
  const std::size_t magic_end = bytes.find('\n') + 1;
  const std::size_t header_end = bytes.find('\n', magic_end);
  const nlohmann::json header = nlohmann::json::parse(bytes.substr(magic_end, header_end - magic_end));
  const auto with_grid = [&](int nx, int ny, int nz) {
    nlohmann::json changed = header;
    changed["nx"] = nx;
    changed["ny"] = ny;
    changed["nz"] = nz;
    changed["num_values"] = 6LL * (nx + 1) * (ny + 1) * nz;
    return bytes.substr(0, magic_end) + changed.dump() + bytes.substr(header_end);
  };
  // A count beyond int, or not whole, was cast by the JSON library (undefined behaviour; fuzz/board_fuzzer found
  // it in the board files, which read their counts the same way).
  nlohmann::json huge = header;
  huge["nx"] = 1e30;
  EXPECT_NE(ReadError(bytes.substr(0, magic_end) + huge.dump() + bytes.substr(header_end))
                .find("the LUT header's nx must be a whole number from 0 to 2147483647"),
            std::string::npos);
  // 4097 x 4097 x 4096 nodes: more than an int counts.
  EXPECT_NE(ReadError(with_grid(4096, 4096, 4096)).find("implausibly large"), std::string::npos);
  // 1001 x 1001 x 100 nodes (601 million values) announced consistently, 108 given.
  EXPECT_NE(ReadError(with_grid(1000, 1000, 100)).find("promises 601200600 values, the file holds 108"),
            std::string::npos)
      << ReadError(with_grid(1000, 1000, 100));
  // The same with the file ending right after the header, without its newline: the stream is then at its
  // end, where it cannot tell its position (fuzz/lut_fuzzer found 4.8 GB allocated for it).
  const std::string big = with_grid(1000, 1000, 100);
  const std::string header_only = big.substr(0, big.find('\n', magic_end));
  EXPECT_NE(ReadError(header_only).find("promises 601200600 values, the file holds 0"), std::string::npos)
      << ReadError(header_only);
}

TEST(LutSlabImages, OneAlphaAndOneBetaPicturePerSlab) {
  const FrustumLut lut = FilledLinear(Grid(4, 3, 3, DepthSpacing::kUniformZ));
  testing::TempDir dir;
  WriteLutSlabImages(lut, dir.path(), 64);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "slab_02_alpha.png"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "slab_00_beta.png"));
  const LutSlabImages images = RenderLutSlabs(lut, 64);
  EXPECT_EQ(images.alpha[0].rows, 48);
  EXPECT_GT(images.alpha_scale, 0.0);
}

}  // namespace
}  // namespace lutex
