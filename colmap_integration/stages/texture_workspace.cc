#include "colmap_integration/stages/texture_workspace.h"

#include <iomanip>
#include <chrono>
#include <stdexcept>
#include <string>

#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/io/workspace.h"
#include "colmap_integration/stages/model_up.h"
#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/stage_memory.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/geometry/mesh_io.h"
#include "lib/geo/map_frame.h"
#include "lib/util/logging.h"
#include "lib/util/option_error.h"
#include "texturing/textured_mesh_io.h"

namespace lutex {

namespace fs = std::filesystem;

void TextureOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (mesh.empty()) throw OptionError("{mesh} is required");
  if (!output.empty()) CheckTexturedMeshPath(output);
  if (!output.empty()) gltf.CheckOutput(output);
  if (page_encoding == ImageEncoding::kFloat) throw std::invalid_argument("pages are srgb8 or linear16");
  CheckUpAxis(up_axis);
  baking.Check();
}

namespace {

// What texture reads and writes (output_policy.h): the images it textures from are found later (restored
// or not), so both candidate folders count as inputs.
InputsAndOutputs PathsOf(const TextureOptions& options, const Workspace& workspace) {
  InputsAndOutputs paths = ViewStageInputs(workspace, options.mesh, options.views, "the images to texture from");
  paths.AddOutput(options.output.empty() ? workspace.ModelPath() : options.output);
  return paths;
}

// The baking options with the most pages `output`'s format holds (a textured PLY: one).
TextureBakingOptions BakingFor(const fs::path& output, TextureBakingOptions baking) {
  if (output.extension() == ".ply") {
    baking.max_pages = 1;
    baking.max_pages_reason = output.string() + " is a textured PLY, which holds one page";
  }
  return baking;
}

}  // namespace

TextureSummary TextureWorkspace(const TextureOptions& options) {
  options.Check();
  PathsOf(options, FindWorkspace(options.workspace)).Check();
  return TextureWorkspace(options, LoadedDive(options.workspace, options.mesh));
}

TextureSummary TextureWorkspace(const TextureOptions& options, const LoadedDive& dive) {
  options.Check();
  const InputsAndOutputs paths = PathsOf(options, dive.workspace());
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(dive.workspace(), paths);
  CheckStageMemory("texture", dive, options.baking.num_threads, kImageStageBytesPerPixel, options.memory_limit_bytes,
                   TextureBakingMemory(options.baking, dive.mesh().faces.size()));
  const fs::path output = options.output.empty() ? dive.workspace().ModelPath() : options.output;
  CheckAtlasFits(dive.mesh(), BakingFor(output, options.baking));
  const auto start = std::chrono::steady_clock::now();
  const Workspace& workspace = dive.workspace();
  const SparseModel& model = dive.model();
  const WorkspaceViews found = FindWorkspaceViews(workspace, model, options.views, "texture");
  const std::vector<TextureView>& views = found.views;
  TextureSummary summary;
  summary.images = found.images;
  summary.confidence = found.confidence;
  const ViewImageSource source = found.Source();
  summary.georeference = ResolveGeoreference(options.georeference, workspace);
  if (summary.georeference.georeference.IsSet()) MapFrame{summary.georeference.georeference};  // checks the CRS
  summary.up = ResolveModelUp(options.up_axis, summary.georeference, model);
  TextureBakingResult result = BakeTexture(dive.mesh(), dive.scene(), views, source, BakingFor(output, options.baking));
  summary.baking = result.summary;
  result.textured.up = summary.up.up;
  result.textured.georeference = summary.georeference.georeference;
  summary.written = WriteTexturedMesh(result.textured, output, options.page_encoding, options.gltf);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void PrintTextureSummary(std::ostream& out, const TextureSummary& summary) {
  const TextureBakingSummary& baking = summary.baking;
  out << std::fixed << std::setprecision(1) << "texture: " << baking.num_textured_faces << " of "
            << baking.num_faces << " faces textured from " << baking.num_views << " images in " << summary.seconds
            << " s\n"
            << "  charts: " << baking.num_charts << " on " << baking.num_pages << " page(s), "
            << double(baking.page_texels) / 1e6 << " Mtexels (" << std::setprecision(0)
            << 100.0 * double(baking.num_texels) / double(std::max<std::size_t>(baking.page_texels, 1))
            << " % on the surface)\n"
            << std::setprecision(2) << "  view selection: energy " << baking.selection.data_cost << " data + "
            << baking.selection.smoothness_cost << " seams (best view per face: "
            << baking.selection.best_view_data_cost << " + " << baking.selection.best_view_smoothness_cost << "), "
            << baking.selection.iterations << " sweeps"
            << (baking.selection.num_regions > 1 ? " (the most in one of " + std::to_string(baking.selection.num_regions) + " regions)" : "")
            << "\n"
            << "  fusion: " << baking.fusion.mean_samples_per_texel << " views per texel, "
            << baking.fusion.rejected_samples << " outlier samples rejected, " << baking.fusion.texels_without_samples
            << " texels seen by no view, " << baking.fusion.num_passes << " pass(es)\n"
            << "  seam levelling: " << DescribeSeamLevelling(baking.levelling) << "\n"
            << std::setprecision(2) << "  seams: " << baking.seams.num_seam_edges << " chart-border edges; colour step "
            << 100.0 * baking.seams.seam_step << " % of full scale across them, " << 100.0 * baking.seams.interior_step
            << " % inside charts\n"
            << std::setprecision(1) << "  time: visibility " << baking.seconds_visibility << " s, view selection "
            << baking.seconds_selection << " s, seam levelling " << baking.levelling.seconds
            << " s, charts and atlas " << baking.seconds_layout << " s, colours " << baking.seconds_fusion
            << " s, writing "
            << summary.seconds - baking.seconds_visibility - baking.seconds_selection - baking.levelling.seconds -
                   baking.seconds_layout - baking.seconds_fusion
            << " s (incl. reading the mesh)\n"
            << "  images: " << summary.images.string() << "\n"
            << "  confidence: " << (summary.confidence.empty() ? std::string("not used") : summary.confidence.string())
            << "\n";
  out << "  georeference: " << summary.georeference.georeference.Describe() << " from " << summary.georeference.source
      << " (recorded in the GLB's asset.extras.lutex)\n";
  out << "  up: " << DescribeModelUp(summary.up, summary.georeference) << "; the GLB turns it to glTF's +Y\n";
  for (const auto& path : summary.written) out << "  wrote " << path.string() << "\n";
}

}  // namespace lutex
