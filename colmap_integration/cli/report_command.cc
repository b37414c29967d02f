#include "colmap_integration/cli/report_command.h"

#include <iostream>

#include "colmap_integration/cli/option_parser.h"
#include "colmap_integration/stages/report_workspace.h"

namespace lutex {

int RunReportCommand(int argc, char** argv) {
  ReportOptions options;
  OptionParser parser(
      "lutex report --workspace W [--lut L] [--output DIR]",
      "Writes one self-contained HTML page (pictures embedded; no network needed to view it) about what\n"
      "lutex did in the workspace W: the run's stages and times, the calibration's residuals (numbers and\n"
      "histograms per constraint type), the LUT's alpha and beta per slab and channel, the coverage of the\n"
      "LUT by calibration data, before/after pictures of a sample of images with their confidence maps, and\n"
      "the atlas pages of the textured model. lutex run writes it at the end; run this after the single\n"
      "commands. Parts not computed yet say so.");
  parser.AddPath("workspace", &options.workspace, "COLMAP workspace that lutex wrote W/lutex/ into.", true);
  parser.AddPath("lut", &options.lut, "The LUT to show (default W/lutex/calibration/lut.lut).");
  parser.AddPath("output", &options.output, "Report folder (default W/lutex/report).");
  parser.AddInt("samples", &options.num_samples, "Images shown before and after.");
  parser.NameField("num_samples", "samples");
  parser.AddInt("thumbnail-width", &options.thumbnail_width, "Width of their pictures, pixels.");
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] {
    const ReportSummary summary = WriteReport(options);
    std::cout << "report: " << summary.num_pictures << " pictures, " << summary.bytes / 1024 << " KiB\n  "
              << summary.index.string() << "\n";
  });
  return 0;
}

}  // namespace lutex
