#pragma once

// `lutex report`: one self-contained HTML page (pictures embedded as data URIs, no scripts, no network)
// about what lutex did in a workspace, under W/lutex/report/index.html:
//   - the run: every stage's status, time and summary (W/lutex/run/*.json);
//   - calibration: observation counts, residuals, iterations per level (calibration_summary.json), residual
//     histograms per constraint type and channel, the LUT's alpha and beta per slab and channel, and the
//     coverage of every slab by calibration data;
//   - restoration: a sample of images before and after, with their confidence maps;
//   - texture: the atlas pages of the textured model (model.glb);
//   - mosaic: the orthomosaic and the DEM, north up, with scale bars (map_previews.h).
// Parts that are missing (a stage not run yet) say so instead of failing.

#include <cstddef>
#include <filesystem>

namespace lutex {

struct ReportOptions {
  std::filesystem::path workspace;
  // The LUT to show; empty: W/lutex/calibration/lut.lut (its coverage.lut beside it).
  std::filesystem::path lut;
  // The report folder; empty: W/lutex/report.
  std::filesystem::path output;
  // Images shown before/after, spread evenly over the model's images by name.
  int num_samples = 6;
  // Width of the thumbnails, pixels.
  int thumbnail_width = 320;

  void Check() const;
};

struct ReportSummary {
  std::filesystem::path index;
  std::size_t num_pictures = 0;
  std::size_t bytes = 0;
};

ReportSummary WriteReport(const ReportOptions& options);

}  // namespace lutex
