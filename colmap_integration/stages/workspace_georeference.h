#pragma once

// The georeference of a workspace's model (lib/geo/georeference.h), from the options of a command or
// from the workspace's georeference file:
//
//   --crs C --crs-origin E,N,H     projected: model + origin = map coordinates in C (origin 0 without
//                                   --crs-origin: the model is in C's coordinates already)
//   --enu-origin LAT,LON,H [--crs C]   a local ENU frame at that point; map products in C, else the
//                                   origin's UTM zone
//   --crs C alone on a workspace whose W/georef.json is ENU: that frame, with its maps in C
//   neither                         W/georef.json when it exists, else none (the model's own frame)

#include <string>

#include "colmap_integration/io/workspace.h"
#include "lib/geo/georeference.h"

namespace lutex {

struct GeoreferenceOptions {
  std::string crs;
  std::string crs_origin;
  std::string enu_origin;
  // Throws OptionError for a combination that says two things ({crs_origin} without {crs}, both
  // origins) or an origin that is not three numbers.
  void Check() const;
};

struct WorkspaceGeoreference {
  Georeference georeference;
  std::string source;  // "the options", "W/georef.json" or "none"
};

// Throws what Check() throws, and what reading the georeference file throws.
WorkspaceGeoreference ResolveGeoreference(const GeoreferenceOptions& options, const Workspace& workspace);

}  // namespace lutex
