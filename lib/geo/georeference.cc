#include "lib/geo/georeference.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "lib/util/file_streams.h"
#include "lib/util/json_fields.h"

namespace lutex {

using nlohmann::json;

std::string FrameName(Georeference::Frame frame) {
  switch (frame) {
    case Georeference::Frame::kNone: return "none";
    case Georeference::Frame::kProjected: return "projected";
    case Georeference::Frame::kEnu: return "enu";
  }
  return "none";
}

std::string Georeference::Describe() const {
  char text[256];
  switch (frame) {
    case Frame::kNone: return "none (the model's own frame)";
    case Frame::kProjected:
      std::snprintf(text, sizeof(text), "%s + (%.3f, %.3f, %.3f)", crs.c_str(), origin.x(), origin.y(), origin.z());
      return text;
    case Frame::kEnu:
      std::snprintf(text, sizeof(text), "ENU at %.7f %c, %.7f %c, %.3f m", std::abs(origin.x()),
                    origin.x() >= 0.0 ? 'N' : 'S', std::abs(origin.y()), origin.y() >= 0.0 ? 'E' : 'W', origin.z());
      return std::string(text) + (crs.empty() ? "" : ", maps in " + crs);
  }
  return "none";
}

Eigen::Vector3d ParseTriple(const std::string& text, const std::string& what) {
  Eigen::Vector3d values;
  std::istringstream stream(text);
  for (int i = 0; i < 3; ++i) {
    if (i > 0) {
      char comma = 0;
      if (!(stream >> comma) || comma != ',') {
        throw std::invalid_argument(what + " must be three numbers X,Y,Z, not '" + text + "'");
      }
    }
    if (!(stream >> values[i]) || !std::isfinite(values[i])) {
      throw std::invalid_argument(what + " must be three numbers X,Y,Z, not '" + text + "'");
    }
  }
  stream >> std::ws;
  if (!stream.eof()) throw std::invalid_argument(what + " must be three numbers X,Y,Z, not '" + text + "'");
  return values;
}

void CheckGeoreference(const Georeference& georeference) {
  if (!georeference.origin.allFinite()) throw std::invalid_argument("the georeference's origin is not finite");
  if (georeference.frame == Georeference::Frame::kProjected && georeference.crs.empty()) {
    throw std::invalid_argument("a projected georeference needs a CRS (e.g. EPSG:32632)");
  }
  if (georeference.frame == Georeference::Frame::kEnu) {
    if (std::abs(georeference.origin.x()) > 90.0) {
      throw std::invalid_argument("the ENU origin's latitude must be in [-90, 90] degrees (LAT,LON,H)");
    }
    if (georeference.origin.y() < -180.0 || georeference.origin.y() > 360.0) {
      throw std::invalid_argument("the ENU origin's longitude must be in [-180, 360] degrees (LAT,LON,H)");
    }
  }
}

Georeference ReadGeoreference(const std::filesystem::path& path) {
  return ReadJsonFile(path, "georeference file", [](const json& root, const std::filesystem::path&) {
    ExpectKeys(root, "", {"frame", "crs", "origin"});
    Georeference georeference;
    const std::string frame = TextField(root, "frame", "", "");
    if (frame == "projected") {
      georeference.frame = Georeference::Frame::kProjected;
    } else if (frame == "enu") {
      georeference.frame = Georeference::Frame::kEnu;
    } else {
      throw JsonFieldError("frame must be \"projected\" or \"enu\", not \"" + frame + "\"");
    }
    georeference.crs = TextField(root, "crs", "", "");
    if (!root.contains("origin")) throw JsonFieldError("origin is required");
    georeference.origin = Vector3Field(root, "origin", "", Eigen::Vector3d::Zero());
    CheckGeoreference(georeference);
    return georeference;
  });
}

void WriteGeoreference(const Georeference& georeference, const std::filesystem::path& path) {
  CheckGeoreference(georeference);
  if (!georeference.IsSet()) throw std::invalid_argument("a georeference file holds a projected or ENU frame");
  json root = {{"frame", FrameName(georeference.frame)},
               {"origin", {georeference.origin.x(), georeference.origin.y(), georeference.origin.z()}}};
  if (!georeference.crs.empty()) root["crs"] = georeference.crs;
  WriteFileAtomically(path, std::ios::out, [&](std::ostream& stream) {
    stream << root.dump(2) << "\n";
  });
}

}  // namespace lutex
