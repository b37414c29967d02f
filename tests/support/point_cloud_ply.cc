#include "tests/support/point_cloud_ply.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace lutex::testing {

std::vector<Eigen::Vector3d> ReadPlyPointPositions(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw std::runtime_error(path.string() + ": cannot open");
  std::string line;
  bool binary = false, in_vertex = false;
  std::size_t count = 0, stride = 0;
  int x_offset = -1;
  while (std::getline(stream, line) && line != "end_header") {
    std::istringstream fields(line);
    std::string keyword;
    fields >> keyword;
    if (keyword == "format") {
      std::string format;
      fields >> format;
      binary = format == "binary_little_endian";
    } else if (keyword == "element") {
      std::string name;
      fields >> name;
      in_vertex = name == "vertex";
      if (in_vertex) fields >> count;
    } else if (keyword == "property" && in_vertex) {
      std::string type, name;
      fields >> type >> name;
      if (name == "x") x_offset = static_cast<int>(stride);
      stride += (type == "float" || type == "float32" || type == "int") ? 4 : (type == "double" ? 8 : 1);
    }
  }
  if (x_offset < 0) throw std::runtime_error(path.string() + ": no vertex x property");
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < count; ++i) {
    if (binary) {
      std::vector<char> record(stride);
      stream.read(record.data(), static_cast<std::streamsize>(stride));
      float xyz[3];
      std::memcpy(xyz, record.data() + x_offset, sizeof(xyz));
      points.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else {
      double x, y, z;
      std::getline(stream, line);
      std::istringstream(line) >> x >> y >> z;
      points.emplace_back(x, y, z);
    }
  }
  return points;
}

}  // namespace lutex::testing
