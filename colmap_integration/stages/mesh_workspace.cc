#include "colmap_integration/stages/mesh_workspace.h"

#include <chrono>
#include <iomanip>

#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/geometry/mesh_io.h"
#include "lib/geometry/ply_io.h"
#include "lib/util/file_streams.h"
#include "lib/geometry/up_direction.h"
#include "lib/util/option_error.h"

namespace lutex {

namespace fs = std::filesystem;

void MeshOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (up_axis != "auto" && !AxisFromName(up_axis)) {
    throw OptionError("{up_axis} must be auto, x, -x, y, -y, z or -z, not '" + up_axis + "'");
  }
  if (!output.empty() && output.extension() != ".ply") throw OptionError("{output} must be a .ply");
  try {
    surface.Check();
  } catch (const std::invalid_argument& error) {
    throw OptionError(error.what());
  }
  georeference.Check();
}

fs::path DenseMeshOf(const Workspace& workspace) {
  for (const DenseWorkspace& dense : workspace.dense) {
    if (!dense.meshes.empty()) return dense.meshes.front();
  }
  return {};
}

MeshSummary MeshWorkspace(const MeshOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const Workspace workspace = FindWorkspace(options.workspace);
  MeshSummary summary;
  summary.output = options.output.empty() ? workspace.MeshPath() : options.output;
  InputsAndOutputs paths;
  paths.AddWorkspace(workspace, "the workspace");
  paths.AddInput(workspace.GeoreferencePath(), "the georeference file");
  paths.AddOutput(summary.output);
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(workspace, paths);
  const SparseModel model = ReadSparseModel(workspace.sparse_dir);
  const WorkspaceGeoreference georeference = ResolveGeoreference(options.georeference, workspace);
  if (options.up_axis != "auto") {
    summary.up = *AxisFromName(options.up_axis);
    summary.up_source = "given";
  } else if (georeference.georeference.IsSet()) {
    summary.up = Eigen::Vector3d::UnitZ();
    summary.up_source = "the georeferenced frame";
  } else {
    try {
      summary.up = UpFromCameras(model);
    } catch (const std::invalid_argument& error) {
      throw OptionError(std::string(error.what()) + "; give the model's up axis with {up_axis}");
    }
    summary.up_source = "the cameras";
  }
  summary.points = workspace.sparse_dir;
  for (const DenseWorkspace& dense : workspace.dense) {
    if (!dense.fused_ply.empty()) {
      summary.points = dense.fused_ply;
      break;
    }
  }
  SparseSurface surface;
  try {
    if (summary.points == workspace.sparse_dir) {
      surface = SurfaceFromSparsePoints(model, summary.up, options.surface);
    } else {
      const Mesh cloud = ParseFile(summary.points, std::ios::binary, [](std::istream& stream) { return ReadPly(stream); });
      surface = SurfaceFromPointCloud(cloud.vertices, model, summary.up, options.surface);
    }
  } catch (const std::invalid_argument& error) {
    throw std::runtime_error(summary.points.string() + ": " + error.what());
  }
  summary.surface = surface.summary;
  WriteMesh(surface.mesh, summary.output);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void PrintMeshSummary(std::ostream& out, const MeshSummary& summary) {
  const SparseSurfaceSummary& s = summary.surface;
  out << std::fixed << std::setprecision(1) << "mesh: " << s.num_faces << " faces, " << s.num_vertices
      << " vertices from " << s.kept_points << " of " << s.num_points << " points of " << summary.points.string()
      << " in " << summary.seconds << " s\n";
  out << "  dropped: " << s.short_tracks << " seen in too few images, " << s.large_errors
      << " with large reprojection errors, " << s.outside_footprint << " under no image, " << s.outliers
      << " off the local surface\n";
  out << std::setprecision(4) << "  height field: " << s.grid_width << " x " << s.grid_height << " nodes of "
      << s.resolution << " m; " << s.footprint_cells << " under the images, " << std::setprecision(1)
      << 100.0 * double(s.cells_with_points) / double(std::max<std::size_t>(s.footprint_cells, 1))
      << " % with points (the rest filled smoothly); rms residual " << std::setprecision(4) << s.rms_residual << " m\n";
  const double not_25d = 100.0 * double(s.steep_cells + s.layered_cells) / double(std::max<std::size_t>(s.footprint_cells, 1));
  out << std::setprecision(2) << "  2.5-D check: " << s.steep_cells << " cells steeper than 60 degrees, "
      << s.layered_cells << " with points well above and below the surface (" << not_25d << " %)"
      << (not_25d > 1.0 ? ": walls or overhangs that a height field smooths over; a dense mesh (COLMAP's on a GPU "
                          "machine, OpenMVS) will be truer there"
                        : ": the survey is a terrain seen from above")
      << "\n";
  out << "  up: " << DirectionName(summary.up) << " of the model (" << summary.up_source << ")\n";
  out << "  wrote " << summary.output.string() << "\n";
}

}  // namespace lutex
