#include "colmap_integration/stages/workspace_georeference.h"

#include <filesystem>
#include <stdexcept>

#include "lib/util/option_error.h"

namespace lutex {

void GeoreferenceOptions::Check() const {
  if (!crs_origin.empty() && crs.empty()) throw OptionError("{crs_origin} needs {crs}");
  if (!crs_origin.empty() && !enu_origin.empty()) {
    throw OptionError("{crs_origin} and {enu_origin} say two different frames: give one");
  }
  try {
    if (!crs_origin.empty()) ParseTriple(crs_origin, "the CRS origin");
    if (!enu_origin.empty()) ParseTriple(enu_origin, "the ENU origin");
  } catch (const std::invalid_argument& error) {
    throw OptionError(std::string(error.what()) + " ({" + (crs_origin.empty() ? "enu_origin" : "crs_origin") + "})");
  }
}

namespace {

// The options' georeference, else the file's, else none.
WorkspaceGeoreference ResolveGiven(const GeoreferenceOptions& options, const Workspace& workspace) {
  options.Check();
  WorkspaceGeoreference resolved;
  Georeference& georeference = resolved.georeference;
  if (!options.enu_origin.empty()) {
    georeference.frame = Georeference::Frame::kEnu;
    georeference.origin = ParseTriple(options.enu_origin, "the ENU origin");
    georeference.crs = options.crs;
  } else if (!options.crs.empty()) {
    georeference.frame = Georeference::Frame::kProjected;
    georeference.crs = options.crs;
    if (!options.crs_origin.empty()) georeference.origin = ParseTriple(options.crs_origin, "the CRS origin");
  }
  if (georeference.IsSet()) {
    try {
      CheckGeoreference(georeference);
    } catch (const std::invalid_argument& error) {
      throw OptionError(std::string(error.what()) + " ({enu_origin})");
    }
    resolved.source = "the options";
    return resolved;
  }
  const std::filesystem::path file = workspace.GeoreferencePath();
  if (std::filesystem::exists(file)) {
    georeference = ReadGeoreference(file);
    resolved.source = file.string();
    return resolved;
  }
  resolved.source = "none";
  return resolved;
}

}  // namespace

WorkspaceGeoreference ResolveGeoreference(const GeoreferenceOptions& options, const Workspace& workspace) {
  // --crs alone on a workspace whose file says ENU chooses the maps' CRS of that frame; it does not
  // declare the model projected at origin 0.
  if (!options.crs.empty() && options.crs_origin.empty() && options.enu_origin.empty()) {
    const std::filesystem::path file = workspace.GeoreferencePath();
    if (std::filesystem::exists(file)) {
      WorkspaceGeoreference resolved{ReadGeoreference(file), file.string() + " with the map CRS of the options"};
      if (resolved.georeference.frame == Georeference::Frame::kEnu) {
        resolved.georeference.crs = options.crs;
        return resolved;
      }
    }
  }
  return ResolveGiven(options, workspace);
}

}  // namespace lutex
