#include "colmap_integration/stages/report_workspace.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "colmap_integration/io/confidence_map_io.h"
#include "colmap_integration/stages/map_previews.h"
#include "colmap_integration/stages/restore_workspace.h"
#include "colmap_integration/io/sparse_model_io.h"
#include "colmap_integration/stages/stage_record.h"
#include "colmap_integration/io/workspace.h"
#include "colmap_integration/stages/output_policy.h"
#include "colmap_integration/stages/workspace_lock.h"
#include "lib/image/image_io.h"
#include "lib/lut/lut_file.h"
#include "lib/lut/lut_slab_images.h"
#include "lib/util/file_streams.h"
#include "lib/util/logging.h"
#include "lib/util/option_error.h"
#include "texturing/gltf_texture_pages.h"

namespace lutex {

namespace fs = std::filesystem;

namespace {

std::string Escape(const std::string& text) {
  std::string escaped;
  for (const char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

std::string Base64(const std::vector<unsigned char>& bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string encoded;
  encoded.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t chunk = (std::uint32_t{bytes[i]} << 16) |
                                (i + 1 < bytes.size() ? std::uint32_t{bytes[i + 1]} << 8 : 0u) |
                                (i + 2 < bytes.size() ? std::uint32_t{bytes[i + 2]} : 0u);
    encoded += kAlphabet[(chunk >> 18) & 63];
    encoded += kAlphabet[(chunk >> 12) & 63];
    encoded += i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
    encoded += i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
  }
  return encoded;
}

// Collects the page's pictures as <img> tags with data URIs.
class PictureEmbedder {
 public:
  // JPEG for photographs, PNG for LUT pictures (sharp, few colours).
  std::string Image(const cv::Mat& bgr8, const std::string& title, bool photograph) {
    std::vector<unsigned char> bytes;
    if (photograph) {
      cv::imencode(".jpg", bgr8, bytes, {cv::IMWRITE_JPEG_QUALITY, 85});
    } else {
      cv::imencode(".png", bgr8, bytes);
    }
    ++count_;
    return "<img src=\"data:image/" + std::string(photograph ? "jpeg" : "png") + ";base64," + Base64(bytes) +
           "\" title=\"" + Escape(title) + "\" alt=\"" + Escape(title) + "\">";
  }
  std::size_t count() const { return count_; }

 private:
  std::size_t count_ = 0;
};

cv::Mat Resized(const cv::Mat& picture, int width) {
  if (picture.cols <= width) return picture;
  cv::Mat resized;
  const int height = std::max(1, static_cast<int>(std::lround(double(picture.rows) * width / picture.cols)));
  cv::resize(picture, resized, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  return resized;
}

// An image file as an 8-bit BGR picture for the screen: 8-bit files as they are (sRGB), 16-bit files as
// linear (lutex's linear16) and float files as linear, both sRGB-encoded for display.
cv::Mat DisplayPicture(const fs::path& path, int width) {
  const cv::Mat picture = cv::imread(path.string(), cv::IMREAD_ANYDEPTH | cv::IMREAD_COLOR);
  if (picture.empty()) throw std::runtime_error(path.string() + ": cannot read the image");
  if (picture.depth() == CV_8U) return Resized(picture, width);
  cv::Mat samples = picture;
  if (picture.depth() != CV_16U) picture.convertTo(samples, CV_32F);  // float files, whatever their precision
  const ImageEncoding encoding = picture.depth() == CV_16U ? ImageEncoding::kLinear16 : ImageEncoding::kFloat;
  return Resized(EncodeLinearImage(DecodeLinearImage(samples, encoding), ImageEncoding::kSrgb8), width);
}

// One channel (0 = red) of an 8-bit BGR LUT picture, in false colour.
cv::Mat ChannelPicture(const cv::Mat& bgr, int channel) {
  cv::Mat single, coloured;
  cv::extractChannel(bgr, single, 2 - channel);
  cv::applyColorMap(single, coloured, cv::COLORMAP_VIRIDIS);
  return coloured;
}

// Residual counts as an SVG bar chart, one translucent series per channel.
std::string HistogramSvg(const nlohmann::json& histogram, const std::string& unit) {
  const double range = histogram.at("range").get<double>();
  const auto& counts = histogram.at("counts");
  std::size_t max_count = 1, total = 0;
  for (const auto& channel : counts) {
    for (const auto& count : channel) max_count = std::max(max_count, count.get<std::size_t>());
    for (const auto& count : channel) total += count.get<std::size_t>();
  }
  std::ostringstream svg;
  const int width = 360, height = 140, plot_height = 110;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" class=\"histogram\"><rect width=\"100%\" height=\"100%\" fill=\"#fafafa\"/>";
  if (total == 0) {
    svg << "<text x=\"10\" y=\"60\" font-size=\"12\">no observations of this type</text></svg>";
    return svg.str();
  }
  const char* colours[3] = {"#d62728", "#2ca02c", "#1f77b4"};
  for (std::size_t c = 0; c < counts.size(); ++c) {
    const std::size_t bins = counts[c].size();
    const double bar = double(width) / double(bins);
    for (std::size_t b = 0; b < bins; ++b) {
      const double h = plot_height * counts[c][b].get<double>() / double(max_count);
      svg << "<rect x=\"" << double(b) * bar << "\" y=\"" << plot_height - h << "\" width=\"" << bar << "\" height=\"" << h
          << "\" fill=\"" << colours[c] << "\" fill-opacity=\"0.45\"/>";
    }
  }
  svg << "<line x1=\"" << width / 2 << "\" y1=\"0\" x2=\"" << width / 2 << "\" y2=\"" << plot_height
      << "\" stroke=\"#333\" stroke-dasharray=\"3,3\"/>";
  svg << std::setprecision(3) << "<text x=\"2\" y=\"" << height - 8 << "\" font-size=\"11\">" << -range
      << "</text><text x=\"" << width / 2 - 4 << "\" y=\"" << height - 8 << "\" font-size=\"11\">0</text><text x=\""
      << width - 40 << "\" y=\"" << height - 8 << "\" font-size=\"11\">" << range << "</text><text x=\"" << width / 2 + 8
      << "\" y=\"12\" font-size=\"11\">" << Escape(unit) << "</text></svg>";
  return svg.str();
}

std::string Vector(const nlohmann::json& values, int precision) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(precision);
  for (std::size_t i = 0; i < values.size(); ++i) text << (i ? " / " : "") << values[i].get<double>();
  return text.str();
}

void RunSection(std::ostream& html, const fs::path& records) {
  html << "<h2>Run</h2>\n";
  bool any = false;
  html << "<table><tr><th>stage</th><th>state</th><th>time</th><th>summary</th></tr>\n";
  for (const char* stage : {"raycast", "calibrate", "restore", "texture"}) {
    const std::optional<StoredStageRecord> record = ReadStageRecord(StageRecordPath(records, stage));
    if (!record) continue;
    any = true;
    html << "<tr><td>" << stage << "</td><td>"
         << Escape(record->state == "started" ? "started, not finished" : record->state) << "</td><td>" << std::fixed
         << std::setprecision(1) << record->seconds << " s</td><td><pre>" << Escape(record->summary)
         << "</pre></td></tr>\n";
  }
  html << "</table>\n";
  if (!any) html << "<p class=\"missing\">No run records in " << Escape(records.string()) << " (lutex run keeps them).</p>\n";
}

void CalibrationSection(std::ostream& html, PictureEmbedder& pictures, const fs::path& lut_path) {
  html << "<h2>Calibration</h2>\n";
  const fs::path summary_path = CalibrationSummaryPath(lut_path);
  if (std::ifstream file(summary_path); file) {
    const nlohmann::json summary = nlohmann::json::parse(file);
    html << "<table class=\"numbers\">"
         << "<tr><td>known-colour observations</td><td>" << summary.value("known_color_observations", 0) << "</td></tr>"
         << "<tr><td>correspondences</td><td>" << summary.value("correspondences", 0) << "</td></tr>"
         << "<tr><td>pure-water observations</td><td>" << summary.value("pure_water_observations", 0) << " (from "
         << summary.value("pure_water_images", 0) << " images, " << summary.value("pure_water_images_skipped", 0)
         << " skipped)</td></tr>"
         << "<tr><td>known-colour residual RMS (R / G / B)</td><td>" << Vector(summary.at("known_color_rms"), 4) << "</td></tr>"
         << "<tr><td>correspondence albedo RMS (R / G / B)</td><td>" << Vector(summary.at("correspondence_albedo_rms"), 4)
         << "</td></tr>"
         << "<tr><td>largest pure-water bound excess (R / G / B)</td><td>"
         << Vector(summary.at("pure_water_max_violation"), 5) << "</td></tr>"
         << "<tr><td>LUT nodes covered by data</td><td>" << std::fixed << std::setprecision(0)
         << 100.0 * summary.value("covered_fraction", 0.0) << " %</td></tr>"
         << "<tr><td>solve time</td><td>" << std::setprecision(1) << summary.value("seconds", 0.0) << " s</td></tr>";
    for (const auto& level : summary.value("levels", nlohmann::json::array())) {
      html << "<tr><td>level " << level.at("nx").get<int>() << " x " << level.at("ny").get<int>()
           << ": iterations, final cost (R / G / B)</td><td>" << Vector(level.at("iterations"), 0) << "; "
           << std::scientific << std::setprecision(2);
      for (std::size_t c = 0; c < 3; ++c) html << (c ? " / " : "") << level.at("final_cost")[c].get<double>();
      html << std::fixed << "</td></tr>";
    }
    if (summary.contains("water_prior") && !summary.at("water_prior").value("in_air", false)) {
      const auto& prior = summary.at("water_prior");
      html << "<tr><td>water prior: attenuation of the signal, per m (R / G / B)</td><td>"
           << Vector(prior.at("signal_attenuation_per_m"), 3) << "</td></tr>"
           << "<tr><td>water prior: attenuation of backscatter, per m (R / G / B)</td><td>"
           << Vector(prior.at("backscatter_attenuation_per_m"), 3) << "</td></tr>";
    }
    if (summary.contains("forward_scatter")) {
      const auto& scatter = summary.at("forward_scatter");
      const auto& water = summary.value("reference_water", nlohmann::json::object());
      html << "<tr><td>water: scattering measured, per m</td><td>" << std::setprecision(3)
           << scatter.at("measured_scattering").get<double>() << "; reference water "
           << Escape(water.value("name", std::string("unknown"))) << " (" << Escape(water.value("chosen", std::string("unknown")))
           << ")</td></tr><tr><td>forward scattering taken out, per m (R / G / B)</td><td>"
           << (scatter.value("removed", true) ? Vector(scatter.at("taken_out"), 3) : std::string("none (kept)"))
           << "</td></tr>";
    }
    if (summary.contains("exposure")) {
      const auto& exposure = summary.at("exposure");
      const double reference = exposure.value("exif_reference", 0.0);
      html << "<tr><td>EXIF exposure (t ISO / N<sup>2</sup>)</td><td>";
      if (reference > 0.0) {
        html << "reference " << std::setprecision(4) << reference << " over " << exposure.value("exif_images", 0) << " images";
      } else {
        html << "not used";
      }
      html << "</td></tr>";
      const auto& gains = exposure.value("fitted_gains", nlohmann::json::object());
      if (!gains.empty()) {
        double lowest = 1e300, highest = 0.0;
        for (const auto& [name, gain] : gains.items()) {
          lowest = std::min(lowest, gain.get<double>());
          highest = std::max(highest, gain.get<double>());
        }
        html << "<tr><td>exposure gains fitted per image</td><td>" << gains.size() << " images, " << std::setprecision(3)
             << lowest << " to " << highest << "</td></tr>";
      }
    }
    html << "</table>\n";
    for (const auto& warning : summary.value("warnings", nlohmann::json::array())) {
      html << "<p class=\"warning\">" << Escape(warning.get<std::string>()) << "</p>\n";
    }
    if (summary.contains("residual_histograms")) {
      const auto& histograms = summary.at("residual_histograms");
      html << "<h3>Residuals after the solve</h3><p>Per channel (red, green, blue, translucent), counts in bins; the "
              "outermost bins also hold everything beyond.</p><div class=\"row\">";
      html << "<figure>" << HistogramSvg(histograms.at("known_color"), "predicted - observed intensity")
           << "<figcaption>known colour</figcaption></figure>";
      html << "<figure>" << HistogramSvg(histograms.at("correspondence_albedo_difference"), "albedo view 1 - view 2")
           << "<figcaption>correspondences</figcaption></figure>";
      html << "<figure>" << HistogramSvg(histograms.at("pure_water_excess"), "beta - pure-water intensity")
           << "<figcaption>pure-water bounds (negative = kept)</figcaption></figure></div>\n";
    }
  } else {
    html << "<p class=\"missing\">No calibration summary at " << Escape(summary_path.string()) << ".</p>\n";
  }
  if (!fs::exists(lut_path)) {
    html << "<p class=\"missing\">No LUT at " << Escape(lut_path.string()) << ".</p>\n";
    return;
  }
  const FrustumLut lut = ReadLut(lut_path);
  const LutSlabImages slabs = RenderLutSlabs(lut, 120);
  const fs::path coverage_path = CoverageLutPath(lut_path);
  std::vector<cv::Mat> coverage;
  if (fs::exists(coverage_path)) coverage = RenderLutSlabs(ReadLut(coverage_path), 120).alpha;
  const FrustumLutGrid& grid = lut.grid();
  html << "<h3>The LUT</h3><p>" << grid.nx << " x " << grid.ny << " cells, " << grid.nz << " slabs from z = "
       << std::setprecision(2) << grid.z_near << " to " << grid.z_far << " (" << Escape(lut_path.string())
       << "). Each picture is one slab seen as the image (u right, v down), in false colour (viridis) from 0 to "
       << "the largest value of the quantity over the LUT: alpha up to " << std::scientific << slabs.alpha_scale
       << ", beta up to " << slabs.beta_scale << std::fixed
       << ". Coverage: 1 (yellow) where at least four observations constrain a node, 0 (purple) where only "
          "smoothness does.</p>\n<table class=\"slabs\"><tr><th>z</th><th>alpha R</th><th>alpha G</th><th>alpha B</th>"
          "<th>beta R</th><th>beta G</th><th>beta B</th><th>coverage</th></tr>\n";
  for (int k = 0; k < grid.nz; ++k) {
    html << "<tr><td>" << std::setprecision(2) << grid.SlabDepth(k) << "</td>";
    for (int c = 0; c < 3; ++c) {
      html << "<td>" << pictures.Image(ChannelPicture(slabs.alpha[k], c), "alpha slab " + std::to_string(k), false) << "</td>";
    }
    for (int c = 0; c < 3; ++c) {
      html << "<td>" << pictures.Image(ChannelPicture(slabs.beta[k], c), "beta slab " + std::to_string(k), false) << "</td>";
    }
    html << "<td>";
    if (!coverage.empty()) html << pictures.Image(ChannelPicture(coverage[k], 0), "coverage slab " + std::to_string(k), false);
    html << "</td></tr>\n";
  }
  html << "</table>\n";
}

void RestorationSection(std::ostream& html, PictureEmbedder& pictures, const Workspace& workspace,
                        const ReportOptions& options) {
  html << "<h2>Restoration</h2>\n";
  const fs::path restored = workspace.RestoredDir();
  const fs::path confidence = ConfidenceDirOf(restored);
  if (!fs::is_directory(restored)) {
    html << "<p class=\"missing\">No restored images in " << Escape(restored.string()) << ".</p>\n";
    return;
  }
  const SparseModel model = ReadSparseModel(workspace.sparse_dir);
  std::vector<std::string> names;
  for (const auto& [id, image] : model.images) names.push_back(image.name);
  std::sort(names.begin(), names.end());
  const std::size_t shown = std::min<std::size_t>(names.size(), static_cast<std::size_t>(options.num_samples));
  html << "<p>" << shown << " of " << names.size()
       << " images, before (as taken) and after (albedo), with the confidence of the restoration (white = fully "
          "trusted; dark where the signal is weak, the pixel saturated, the surface grazing or the LUT not "
          "constrained by calibration data; black where there is no surface).</p>\n<table class=\"samples\">"
          "<tr><th>image</th><th>before</th><th>after</th><th>confidence</th></tr>\n";
  for (std::size_t s = 0; s < shown; ++s) {
    const std::string& name = names[shown == 1 ? 0 : s * (names.size() - 1) / (shown - 1)];
    html << "<tr><td>" << Escape(name) << "</td><td>"
         << pictures.Image(DisplayPicture(workspace.images_dir / name, options.thumbnail_width), name + " before", true)
         << "</td><td>";
    const fs::path after = FindRestoredImage(restored, name);
    if (after.empty()) {
      html << "not restored";
    } else {
      html << pictures.Image(DisplayPicture(after, options.thumbnail_width), name + " after", true);
    }
    html << "</td><td>";
    const fs::path confidence_map = ConfidenceMapPath(confidence, name);
    if (fs::exists(confidence_map)) {
      html << pictures.Image(DisplayPicture(confidence_map, options.thumbnail_width), name + " confidence", true);
    }
    html << "</td></tr>\n";
  }
  html << "</table>\n";
}

void TextureSection(std::ostream& html, PictureEmbedder& pictures, const Workspace& workspace) {
  html << "<h2>Texture</h2>\n";
  const fs::path model = workspace.ModelPath();
  if (!fs::exists(model)) {
    html << "<p class=\"missing\">No textured model at " << Escape(model.string()) << ".</p>\n";
    return;
  }
  const std::vector<cv::Mat> pages = ReadGltfTexturePages(model);
  html << "<p>" << Escape(model.string()) << ": " << pages.size()
       << " atlas page(s) (grey: texels no chart uses). Open the model in any glTF viewer (e.g. Blender: File › "
          "Import › glTF 2.0).</p><div class=\"row\">\n";
  for (std::size_t p = 0; p < pages.size(); ++p) {
    html << "<figure>" << pictures.Image(Resized(pages[p], 1024), "page " + std::to_string(p), true)
         << "<figcaption>page " << p << ": " << pages[p].cols << " x " << pages[p].rows << "</figcaption></figure>\n";
  }
  html << "</div>\n";
}

void MosaicSection(std::ostream& html, PictureEmbedder& pictures, const Workspace& workspace) {
  html << "<h2>Mosaic</h2>\n";
  const fs::path ortho = workspace.OrthomosaicPath(), dem = workspace.DemPath();
  if (!fs::exists(ortho)) {
    html << "<p class=\"missing\">No orthomosaic at " << Escape(ortho.string()) << ".</p>\n";
    return;
  }
  const MapPreview colours = OrthomosaicPreview(ortho, 1024);
  html << "<p>" << Escape(ortho.string()) << (fs::exists(dem) ? " and " + Escape(dem.string()) : std::string())
       << ": Cloud-Optimized GeoTIFFs, north up, in "
       << (colours.crs_name.empty() ? std::string("the model's own frame (no CRS)") : Escape(colours.crs_name))
       << " (open them in QGIS: Layer › Add Layer › Add Raster Layer). Grey: no image sees the surface there."
       << "</p><div class=\"row\">\n";
  html << "<figure>" << pictures.Image(colours.bgr8, "orthomosaic", true) << "<figcaption>orthomosaic (shown at "
       << std::setprecision(3) << colours.metres_per_pixel << " m per pixel)</figcaption></figure>\n";
  if (fs::exists(dem)) {
    const MapPreview heights = DemPreview(dem, 1024);
    html << "<figure>" << pictures.Image(heights.bgr8, "DEM", false) << "<figcaption>DEM: " << std::fixed
         << std::setprecision(3) << heights.low << " m (dark blue) to " << heights.high << " m (yellow)"
         << std::defaultfloat << "</figcaption></figure>\n";
  }
  html << "</div>\n";
}

}  // namespace

void ReportOptions::Check() const {
  if (workspace.empty()) throw OptionError("{workspace} is required");
  if (num_samples < 0) throw OptionError("{num_samples} must not be negative");
  if (thumbnail_width < 16) throw OptionError("{thumbnail_width} must be at least 16");
}

ReportSummary WriteReport(const ReportOptions& options) {
  options.Check();
  const Workspace workspace = FindWorkspace(options.workspace);
  const fs::path lut = options.lut.empty() ? workspace.LutPath() : options.lut;
  const fs::path folder = options.output.empty() ? workspace.ReportDir() : options.output;
  InputsAndOutputs paths;
  paths.AddWorkspace(workspace, "the workspace");
  paths.AddInput(lut, "the LUT");
  paths.AddOutput(folder);
  const std::unique_ptr<ExclusiveFileLock> workspace_lock = ClaimOutputs(workspace, paths);
  PictureEmbedder pictures;
  std::ostringstream html;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>lutex report: "
       << Escape(workspace.root.filename().string()) << "</title>\n<style>\n"
       << "body{font-family:sans-serif;margin:2em;max-width:1400px;color:#222}h1{margin-bottom:0}"
          "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #ccc;padding:4px 8px;vertical-align:top;"
          "text-align:left}pre{margin:0;white-space:pre-wrap;font-size:12px}.missing{color:#a33}.warning{color:#8a5a00}"
          ".row{display:flex;flex-wrap:wrap;gap:1em}figure{margin:0}figcaption{font-size:13px;text-align:center}"
          ".slabs td{padding:2px}.slabs img{display:block}img{max-width:100%}\n"
       << "</style></head><body>\n<h1>lutex report</h1>\n<p>Workspace " << Escape(fs::absolute(workspace.root).string())
       << "; written " << std::put_time(std::gmtime(&now), "%Y-%m-%d %H:%M UTC") << ".</p>\n";
  RunSection(html, workspace.RunRecordsDir());
  CalibrationSection(html, pictures, lut);
  RestorationSection(html, pictures, workspace, options);
  TextureSection(html, pictures, workspace);
  MosaicSection(html, pictures, workspace);
  html << "</body></html>\n";

  ReportSummary summary;
  summary.index = folder / "index.html";
  summary.num_pictures = pictures.count();
  const std::string page = html.str();
  summary.bytes = page.size();
  WriteFileAtomically(summary.index, std::ios::out, [&page](std::ostream& out) { out << page; });
  return summary;
}

}  // namespace lutex
