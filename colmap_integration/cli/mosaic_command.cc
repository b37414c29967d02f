#include "colmap_integration/cli/mosaic_command.h"

#include <iostream>

#include "colmap_integration/cli/dive_options.h"
#include "colmap_integration/cli/image_encoding_option.h"
#include "colmap_integration/cli/texture_command.h"

namespace lutex {

void AddGeoreferenceOptions(OptionParser& parser, GeoreferenceOptions* georeference) {
  parser.AddString("crs", &georeference->crs,
                   "The model's projected CRS (EPSG:32632, or any PROJ text): model x, y, z + --crs-origin =\n"
                   "      easting, northing, height. With --enu-origin: the CRS of the map products instead.");
  parser.AddString("crs-origin", &georeference->crs_origin,
                   "E,N,H added to the model's coordinates to give the CRS's (default 0,0,0).");
  parser.AddString("enu-origin", &georeference->enu_origin,
                   "LAT,LON,H (degrees, metres above the WGS 84 ellipsoid): the model is a local east-north-up\n"
                   "      frame at that point (colmap model_aligner --ref_is_gps 1 --alignment_type enu); map\n"
                   "      products go in its UTM zone unless --crs says otherwise.");
}

void AddMosaicStageOptions(OptionParser& parser, MosaicOptions* options) {
  parser.AddDouble("gsd", &options->gsd,
                   "Metres per pixel of the mosaic in the map CRS; 0 (default) = the images' own (median over\n"
                   "      images of the range at the image centre / the focal length in pixels).");
  AddGeoreferenceOptions(parser, &options->georeference);
  parser.AddIntInRange("tile-size", &options->ortho.tile_size, 16, 8192,
                       "Mosaic pixels per side of a processing tile (memory ~200 bytes per pixel of a tile).\n"
                       "      Tiles are grouped in blocks about an image's footprint wide; a block's views are\n"
                       "      chosen on its own piece of the mesh, so memory does not grow with the area.");
}

int RunMosaicCommand(int argc, char** argv) {
  MosaicOptions options;
  OptionParser parser(
      "lutex mosaic --workspace W --mesh M [--gsd 0.005] [--crs EPSG:N --crs-origin E,N,H | --enu-origin LAT,LON,H]",
      "Maps the seafloor from above: a north-up orthomosaic of the restored albedo and a DEM of the mesh's\n"
      "heights, as Cloud-Optimized GeoTIFFs in the survey's coordinate system, for QGIS, ArcGIS and GDAL.\n"
      "Each pixel is the topmost point of the mesh under its centre; its colour is fused from every image\n"
      "that sees that point, as a texel of lutex texture is (depth-consistent sampling, confidence x angle x\n"
      "resolution weights, outliers rejected). Pixels no image sees are transparent (alpha 0) in the mosaic\n"
      "and NaN in the DEM.\n"
      "Georeference: --crs/--crs-origin or --enu-origin, else W/georef.json, e.g.\n"
      "  {\"frame\": \"projected\", \"crs\": \"EPSG:32632\", \"origin\": [500123.0, 6001234.0, -812.5]}\n"
      "  {\"frame\": \"enu\", \"origin\": [54.3201, 10.1402, 0.0]}\n"
      "else the model's own frame (x east, y north, z up; no CRS).\n"
      "Outputs: W/lutex/mosaic/ortho.tif (8-bit sRGB + alpha; 16-bit linear with --encoding linear16) and\n"
      "W/lutex/mosaic/dem.tif (float32 heights), tiled 512, DEFLATE, with overviews. The grid is processed\n"
      "in tiles, each reading only the images that see it: memory is bounded by the tile size and the image\n"
      "cache, not by the survey's area.");
  AddDiveOptions(parser, &options.workspace, &options.mesh);
  parser.AddPath("images", &options.views.images, "Images to map (default W/lutex/restored, else W/images).");
  AddImageEncodingOption(parser, "image-encoding", &options.views.image_encoding, "How those images are encoded:");
  parser.AddPath("confidence", &options.views.confidence, "Confidence maps (default DIR_confidence when present).");
  parser.AddFlag("no-confidence", &options.views.ignore_confidence, "Trust every pixel equally.");
  parser.AddPath("output", &options.output, "The orthomosaic (default W/lutex/mosaic/ortho.tif).");
  parser.AddPath("dem", &options.dem, "The DEM (default W/lutex/mosaic/dem.tif).");
  parser.AddFlag("no-dem", &options.no_dem, "Write no DEM.");
  parser.AddCustom("encoding", "srgb8", "The mosaic's samples: srgb8 (8-bit sRGB) or linear16 (16-bit linear).",
                   [&options](const std::string& text) { options.encoding = ParseImageEncoding(text); });
  AddMosaicStageOptions(parser, &options);
  AddViewFusionOptions(parser, &options.ortho.baking);
  AddThreadsOption(parser, &options.ortho.baking.num_threads);
  AddMemoryLimitOption(parser, &options.memory_limit_bytes);
  AddImageCacheOption(parser, {&options.picture_cache_bytes});
  if (!parser.Parse(argc, argv, 2)) return 0;
  parser.RunWithFlags([&] { PrintMosaicSummary(std::cout, MosaicWorkspace(options)); });
  return 0;
}

}  // namespace lutex
