// lutex texture on the Blender seafloor (../shared/datasets/dev/seafloor_clear: 36 images of a textured
// terrain, 100k faces). The baked model is rendered back into every camera (lutex's ray caster + the
// texture lookup a viewer does) and compared with gt/albedo, the albedo seen through each pixel.
//   - Texturing alone: baked from the ground-truth albedo images with the true poses and mesh.
//   - Full chain: calibrated from the boards + pure water, restored, baked; fused vs one view per face
//     vs unrestored images, with the colour step across chart borders (seam visibility).
// Skips without the datasets.

#include <cmath>
#include <cstdio>
#include <regex>

#include <gtest/gtest.h>

#include "colmap_integration/stages/calibrate_workspace.h"
#include "colmap_integration/stages/restore_workspace.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/texture_workspace.h"
#include "lib/geometry/mesh_io.h"
#include "lib/image/image_io.h"
#include "lib/raycast/raycast_scene.h"
#include "tests/support/shared_datasets.h"
#include "tests/support/blender_render_back.h"
#include "tests/support/gltf_validator.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"

namespace lutex {
namespace {

namespace fs = std::filesystem;

class BlenderTexture : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto dev = testing::SharedDevDatasets();
    if (!dev) GTEST_SKIP() << "../shared/datasets is absent";
    dev_ = *dev;
    survey_ = dev_ / "seafloor_clear";
  }

  TextureOptions Texturing(const fs::path& images, ImageEncoding encoding, const fs::path& output) const {
    TextureOptions options;
    options.workspace = survey_;
    options.mesh = survey_ / "scene" / "mesh.ply";
    options.views.images = images;
    options.views.image_encoding = encoding;
    options.output = output;
    options.page_encoding = ImageEncoding::kLinear16;
    return options;
  }

  fs::path dev_, survey_;
};

TEST_F(BlenderTexture, GroundTruthAlbedoBakesBackWithinTwoPercent) {
  testing::TempDir dir;
  const TextureSummary summary =
      TextureWorkspace(Texturing(survey_ / "gt" / "albedo", ImageEncoding::kFloat, dir.path() / "model.ply"));
  const testing::RenderBack back = testing::CompareWithGroundTruth(survey_, testing::ReadTexturedPly(dir.path() / "model.ply"));
  std::printf("ground-truth albedo baked: %zu charts, %zu texels; rendered back MAE %.2f pp over %.1f %% of the "
              "surface pixels; seam step %.2f pp\n",
              summary.baking.num_charts, summary.baking.num_texels, back.mae, 100.0 * back.textured_pixels,
              100.0 * summary.baking.seams.Excess());
  EXPECT_LT(back.mae, 2.0);  // the bar
  EXPECT_GT(back.textured_pixels, 0.99);  // every face a camera sees is textured

  // The baked texture against the scene's own texture, face by face (the shared metric).
  const testing::CommandResult metric =
      testing::RunCommand("/usr/bin/python3 '" + (dev_.parent_path().parent_path() / "tools" / "texture_error.py").string() +
                          "' '" + survey_.string() + "' '" + (dir.path() / "model.ply").string() + "' '" +
                          (dir.path() / "model_texture.png").string() + "' --encoding linear16");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(metric.output, match, std::regex("mae=([0-9.]+)"))) << metric.output;
  std::printf("texture_error.py: %s", metric.output.c_str());
  EXPECT_LT(std::stod(match[1]), 2.0);

  // The same bake as GLB passes the Khronos validator.
  TextureWorkspace(Texturing(survey_ / "gt" / "albedo", ImageEncoding::kFloat, dir.path() / "model.glb"));
  const testing::GltfValidation validation = testing::ValidateGltf(dir.path() / "model.glb");
  ASSERT_TRUE(validation.ran) << validation.output;
  EXPECT_TRUE(validation.valid) << validation.output;
}

TEST_F(BlenderTexture, RestoredAndFusedTexturesAreTrueAndSeamless) {
  testing::TempDir dir;
  CalibrateOptions calibrate;
  calibrate.workspace = dev_ / "calib_boards_clear";
  calibrate.mesh = calibrate.workspace / "scene" / "mesh.ply";
  calibrate.targets = calibrate.workspace / "metadata.json";
  calibrate.pure_water = dev_ / "purewater_clear";
  calibrate.input_encoding = ImageEncoding::kLinear16;
  calibrate.calibration.grid.z_near = 0.4;
  calibrate.calibration.grid.z_far = 3.0;
  calibrate.output = dir.path() / "lut.lut";
  const CalibrateSummary calibrated = CalibrateWorkspace(calibrate);
  RestoreOptions restore;
  restore.workspace = survey_;
  restore.mesh = survey_ / "scene" / "mesh.ply";
  restore.lut = calibrated.lut;
  restore.input_encoding = ImageEncoding::kLinear16;
  restore.output = dir.path() / "restored";
  RestoreWorkspace(restore);

  struct Variant {
    const char* name;
    fs::path images;
    TexelBlend blend;
    bool level;  // seam levelling
    testing::RenderBack back;
    double seam_step = 0.0;  // seam visibility: the step across chart borders less that inside charts, pp
    SeamLevellingSummary levelling;
  };
  const fs::path restored = dir.path() / "restored";
  std::vector<Variant> variants = {{"restored, fused", restored, TexelBlend::kFuse, true, {}, 0.0, {}},
                                   {"restored, one view per face", restored, TexelBlend::kSingle, true, {}, 0.0, {}},
                                   {"unrestored, fused", survey_ / "images", TexelBlend::kFuse, true, {}, 0.0, {}},
                                   {"restored, fused, unlevelled", restored, TexelBlend::kFuse, false, {}, 0.0, {}},
                                   {"restored, one view, unlevelled", restored, TexelBlend::kSingle, false, {}, 0.0, {}}};
  for (Variant& variant : variants) {
    TextureOptions options = Texturing(variant.images, ImageEncoding::kLinear16, dir.path() / "model.ply");
    options.baking.fusion.blend = variant.blend;
    options.baking.levelling.enabled = variant.level;
    const TextureSummary summary = TextureWorkspace(options);
    variant.back = testing::CompareWithGroundTruth(survey_, testing::ReadTexturedPly(dir.path() / "model.ply"));
    variant.seam_step = 100.0 * summary.baking.seams.Excess();
    variant.levelling = summary.baking.levelling;
    std::printf("%-31s rendered back MAE %5.2f pp; colour step across %zu chart borders %.2f pp, inside charts "
                "%.2f pp: seam %.2f pp; levelling: %s\n",
                variant.name, variant.back.mae, summary.baking.seams.num_seam_edges,
                100.0 * summary.baking.seams.seam_step, 100.0 * summary.baking.seams.interior_step, variant.seam_step,
                DescribeSeamLevelling(summary.baking.levelling).c_str());
  }
  // Restoration is what makes the texture true (raw images carry the lights and the water).
  EXPECT_LT(variants[0].back.mae, 5.0);  // the restored images themselves: README, 'Accuracy on the Blender seafloor'
  EXPECT_LT(variants[0].back.mae, 0.3 * variants[2].back.mae);
  // The restored views agree to about 1 % at chart borders, so what is left of a seam is mostly not a colour
  // offset (README: the two sides sample the surface at different resolutions, and the views differ in
  // noise). Fusing all views leaves no more than one view per face, and fused or levelled bakes stay below
  // 1.25 pp of seam step (measured 0.97 and 1.09 pp; 0.70 and 0.84 with forward scattering kept in the
  // images, which blurs each view's noise along with its detail).
  EXPECT_LE(variants[3].seam_step, variants[4].seam_step);
  for (const Variant& variant : {variants[0], variants[1], variants[3]}) EXPECT_LT(variant.seam_step, 1.25) << variant.name;
  // Where one view per face leaves a colour step at the seam points, levelling removes at least a fifth of it,
  // and keeps the fused texture as it was (nearly seamless already), without moving either away from the
  // true albedo.
  EXPECT_LT(variants[1].levelling.step_after, 0.8 * variants[1].levelling.step_before);
  EXPECT_LE(variants[1].seam_step, variants[4].seam_step);
  EXPECT_LT(variants[0].seam_step, variants[3].seam_step + 0.05);
  EXPECT_LT(variants[0].back.mae, variants[3].back.mae + 0.05);
  EXPECT_LT(variants[1].back.mae, variants[4].back.mae + 0.05);
}

}  // namespace
}  // namespace lutex
