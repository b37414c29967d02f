#include "colmap_integration/stages/mosaic_workspace.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/stage_memory.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/geo/cog_writer.h"
#include "lib/geo/map_frame.h"
#include "lib/geometry/up_direction.h"
#include "lib/util/logging.h"
#include "lib/util/median.h"
#include "lib/util/parallel_for.h"
#include "lib/util/option_error.h"

namespace lutex {

namespace fs = std::filesystem;

void MosaicOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (mesh.empty()) throw OptionError("{mesh} is required");
  if (!(gsd >= 0.0) || !std::isfinite(gsd)) throw OptionError("{gsd} must be a positive number of metres per pixel");
  if (encoding != ImageEncoding::kSrgb8 && encoding != ImageEncoding::kLinear16) {
    throw OptionError("{encoding} must be srgb8 or linear16");
  }
  if (!output.empty() && output.extension() != ".tif" && output.extension() != ".tiff") {
    throw OptionError("{output} must be a .tif (a Cloud-Optimized GeoTIFF), not '" + output.string() + "'");
  }
  if (!dem.empty() && dem.extension() != ".tif" && dem.extension() != ".tiff") {
    throw OptionError("{dem} must be a .tif (a Cloud-Optimized GeoTIFF), not '" + dem.string() + "'");
  }
  if (no_dem && !dem.empty()) throw OptionError("{no_dem} and {dem} contradict each other");
  georeference.Check();
  ortho.Check();
}

double GsdOfViews(std::vector<double> gsds) {
  gsds.erase(std::remove_if(gsds.begin(), gsds.end(), [](double gsd) { return !std::isfinite(gsd); }), gsds.end());
  if (gsds.empty()) throw OptionError("no image centre sees the mesh: give the mosaic's {gsd}");
  return MedianInPlace(gsds);
}

std::string WhyNotAMapWithoutGeoreference(const SparseModel& model) {
  try {
    const Eigen::Vector3d up = UpFromCameras(model);
    if (up == Eigen::Vector3d::UnitZ()) return "";
    return "the model is not georeferenced and its up (opposite the cameras' view) is " + DirectionName(up) +
           ", not +z";
  } catch (const std::invalid_argument& error) {
    return std::string("the model is not georeferenced and ") + error.what();
  }
}

namespace {

// Blocks' worth of faces in a block's piece, for the memory estimate (see MosaicWorkspace).
constexpr std::size_t kPieceBlocks = 8;

InputsAndOutputs PathsOf(const MosaicOptions& options, const Workspace& workspace) {
  InputsAndOutputs paths = ViewStageInputs(workspace, options.mesh, options.views, "the images to map");
  paths.AddOutput(options.output.empty() ? workspace.OrthomosaicPath() : options.output);
  if (!options.no_dem) paths.AddOutput(options.dem.empty() ? workspace.DemPath() : options.dem);
  return paths;
}

// A tile's colours as the GeoTIFF stores them: R, G, B (sRGB 8-bit or linear 16-bit) and alpha.
cv::Mat RgbaOf(const cv::Mat& colour, ImageEncoding encoding) {
  cv::Mat rgba;
  cv::cvtColor(EncodeLinearImage(colour, encoding), rgba, cv::COLOR_BGR2RGBA);
  const double opaque = encoding == ImageEncoding::kSrgb8 ? 255.0 : 65535.0;
  for (int r = 0; r < colour.rows; ++r) {
    for (int c = 0; c < colour.cols; ++c) {
      const bool seen = std::isfinite(colour.at<cv::Vec3f>(r, c)[0]);
      if (encoding == ImageEncoding::kSrgb8) {
        rgba.at<cv::Vec4b>(r, c)[3] = seen ? static_cast<uchar>(opaque) : 0;
      } else {
        rgba.at<cv::Vec4w>(r, c)[3] = seen ? static_cast<ushort>(opaque) : 0;
      }
    }
  }
  return rgba;
}

}  // namespace

MosaicSummary MosaicWorkspace(const MosaicOptions& options) {
  options.Check();
  PathsOf(options, FindWorkspace(options.workspace)).Check();
  LoadedDive dive(options.workspace, options.mesh);
  return MosaicWorkspace(options, dive);
}

MosaicSummary MosaicWorkspace(const MosaicOptions& options, LoadedDive& dive) {
  options.Check();
  const InputsAndOutputs paths = PathsOf(options, dive.workspace());
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(dive.workspace(), paths);
  const auto start = std::chrono::steady_clock::now();
  const Workspace& workspace = dive.workspace();
  MosaicSummary summary;
  summary.georeference = ResolveGeoreference(options.georeference, workspace);
  const MapFrame frame(summary.georeference.georeference);
  summary.crs = frame.crs();
  summary.crs_name = frame.crs_name();
  WorkspaceViewsOptions views_options = options.views;
  views_options.picture_cache_bytes = options.picture_cache_bytes;
  const WorkspaceViews found = FindWorkspaceViews(workspace, dive.model(), views_options, "mosaic");
  summary.images = found.images;
  summary.confidence = found.confidence;
  if (!frame.HasCrs()) {
    const std::string unfit = WhyNotAMapWithoutGeoreference(dive.model());
    if (!unfit.empty()) throw OptionError(unfit + ": give a georeference ({enu_origin} or {crs})");
    LogWarning() << "mosaic: no georeference (no --crs, --enu-origin or W/georef.json): the mosaic is in the model's "
                    "own frame, with no CRS, and will not sit on a map";
  }
  double gsd = options.gsd;
  summary.gsd_from_images = gsd == 0.0;
  const std::vector<double> gsds_at_centres = GsdsAtImageCentres(dive.mesh(), found.views);  // one pass over the faces
  if (summary.gsd_from_images) gsd = GsdOfViews(gsds_at_centres);
  summary.grid = OrthoGridOfMesh(dive.mesh(), frame, gsd);
  const int tile_size = options.ortho.tile_size;
  OrthoTiling tiling = TileOrthoGrid(dive.mesh(), frame, summary.grid, tile_size,
                                     OrthoBlockSide(gsds_at_centres, found.views, summary.grid, tile_size));
  // A block's views are chosen on its piece, the block and the surface around it within reach of the
  // views that see it (ortho_mosaic.h), taken as kPieceBlocks blocks' worth of the fullest block.
  const std::size_t piece_faces = std::min(dive.mesh().faces.size(), kPieceBlocks * tiling.MostFaces());
  MemoryEstimate baking_memory = TextureBakingMemory(options.ortho.baking, piece_faces);
  baking_memory.Add("the block of every face", static_cast<double>(dive.mesh().faces.size()),
                    sizeof(std::uint32_t));
  baking_memory.Add("the decoded-picture cache", 1.0,
                    PictureCacheBytes(dive.model(), options.views.image_encoding, options.picture_cache_bytes));
  baking_memory.Add("GDAL's block cache", 1.0, static_cast<double>(options.gdal_cache_bytes));
  CheckStageMemory("mosaic", dive, options.ortho.baking.num_threads, kImageStageBytesPerPixel,
                   options.memory_limit_bytes, baking_memory, piece_faces);
  summary.ortho = options.output.empty() ? workspace.OrthomosaicPath() : options.output;
  if (!options.no_dem) summary.dem = options.dem.empty() ? workspace.DemPath() : options.dem;
  LogInfo() << "mosaic: " << summary.grid.raster.width << " x " << summary.grid.raster.height << " pixels at " << gsd
            << " m";

  CheckSurfaceFromAbove(dive.mesh(), frame);
  CogWriter ortho(summary.ortho, summary.grid.raster,
                  options.encoding == ImageEncoding::kSrgb8 ? GeoRasterKind::kRgba8 : GeoRasterKind::kRgba16,
                  options.gdal_cache_bytes);
  std::unique_ptr<CogWriter> dem;
  if (!options.no_dem) {
    dem = std::make_unique<CogWriter>(summary.dem, summary.grid.raster, GeoRasterKind::kFloat32, options.gdal_cache_bytes);
  }
  const ViewImageSource source = found.Source();
  summary.mosaic = MakeOrthoMosaic(dive.mesh(), found.views, source, frame, summary.grid, options.ortho,
                                   [&](const OrthoTile& tile) {
                                     ortho.WriteTile(tile.col, tile.row, RgbaOf(tile.colour, options.encoding));
                                     if (dem) dem->WriteTile(tile.col, tile.row, tile.height);
                                   },
                                   summary.ortho.string() + ".mesh", &tiling, [&] {
                                     dive.ReleaseMesh();
                                     for (std::vector<std::uint32_t>& faces : tiling.faces) {
                                       std::vector<std::uint32_t>().swap(faces);
                                     }
                                   });
  summary.files_decoded = found.pictures->decodes();
  if (summary.mosaic.seen_cells == 0) {
    throw std::runtime_error("mosaic: no image sees the mesh's surface from above; nothing to map");
  }
  const int threads = ResolveNumThreads(options.ortho.baking.num_threads);
  // Both converted before either is renamed: a failure leaves neither new file beside an old one.
  ortho.Convert(threads);
  if (dem) dem->Convert(threads);
  ortho.Commit();
  if (dem) dem->Commit();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void PrintMosaicSummary(std::ostream& out, const MosaicSummary& summary) {
  const GeoRasterGrid& raster = summary.grid.raster;
  const OrthoMosaicSummary& mosaic = summary.mosaic;
  out << std::fixed << std::setprecision(1) << "mosaic: " << raster.width << " x " << raster.height << " pixels at "
      << std::setprecision(4) << raster.gsd << " m" << (summary.gsd_from_images ? " (the images' own GSD)" : "")
      << std::setprecision(1) << " from " << mosaic.num_views << " images in " << summary.seconds << " s\n";
  out << "  map frame: "
      << (summary.crs.empty() ? std::string("the model's own (no CRS)") : summary.crs + " (" + summary.crs_name + ")")
      << "; georeference " << summary.georeference.georeference.Describe() << " from " << summary.georeference.source
      << "\n";
  out << std::setprecision(3) << "  extent: west " << raster.west << ", north " << raster.north << ", "
      << raster.width * raster.gsd << " x " << raster.height * raster.gsd << " m; heights " << summary.grid.bottom
      << " to " << summary.grid.top << " m\n";
  const double cells = double(std::max<std::size_t>(mosaic.num_cells, 1));
  out << std::setprecision(1) << "  cells: " << 100.0 * double(mosaic.surface_cells) / cells << " % over the surface, "
      << 100.0 * double(mosaic.seen_cells) / cells << " % seen (" << std::setprecision(2) << mosaic.mean_samples_per_cell
      << " views per cell); " << mosaic.num_tiles << " tile(s), " << mosaic.tile_view_reads << " image reads, " << summary.files_decoded
      << " images and confidence maps decoded (the rest came from --image-cache)\n";
  out << "  seam levelling: " << DescribeSeamLevelling(mosaic.levelling) << "\n";
  out << std::setprecision(1) << "  time: visibility, view selection and seam levelling in " << mosaic.num_blocks
      << " block(s) of tiles (at most " << mosaic.max_piece_faces << " faces with the surface around a block) "
      << mosaic.seconds_selection << " s; the rest " << mosaic.seconds_tiles << " s\n";
  out << "  images: " << summary.images.string() << "\n"
      << "  confidence: " << (summary.confidence.empty() ? std::string("not used") : summary.confidence.string()) << "\n";
  out << "  wrote " << summary.ortho.string() << "\n";
  if (!summary.dem.empty()) out << "  wrote " << summary.dem.string() << "\n";
}

}  // namespace lutex
