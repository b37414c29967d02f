#include "lib/geometry/ply_io.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace lutex {
namespace {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };
enum class PlyType { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

PlyType ParseType(const std::string& name) {
  if (name == "char" || name == "int8") return PlyType::kInt8;
  if (name == "uchar" || name == "uint8") return PlyType::kUInt8;
  if (name == "short" || name == "int16") return PlyType::kInt16;
  if (name == "ushort" || name == "uint16") return PlyType::kUInt16;
  if (name == "int" || name == "int32") return PlyType::kInt32;
  if (name == "uint" || name == "uint32") return PlyType::kUInt32;
  if (name == "float" || name == "float32") return PlyType::kFloat32;
  if (name == "double" || name == "float64") return PlyType::kFloat64;
  throw std::runtime_error("PLY header: unknown property type '" + name + "'");
}

std::size_t SizeOf(PlyType type) {
  switch (type) {
    case PlyType::kInt8: case PlyType::kUInt8: return 1;
    case PlyType::kInt16: case PlyType::kUInt16: return 2;
    case PlyType::kInt32: case PlyType::kUInt32: case PlyType::kFloat32: return 4;
    case PlyType::kFloat64: return 8;
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool is_list = false;
  PlyType count_type = PlyType::kUInt8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
  int Find(const std::string& property) const {
    for (std::size_t i = 0; i < properties.size(); ++i) {
      if (properties[i].name == property) return static_cast<int>(i);
    }
    return -1;
  }
};

// Reads one value of any PLY type as double, in the file's encoding.
class ValueReader {
 public:
  ValueReader(std::istream& stream, PlyFormat format) : stream_(stream), format_(format) {}

  double Read(PlyType type, const char* where) {
    if (format_ == PlyFormat::kAscii) {
      // strtod, unlike operator>>, reads "nan" and "inf", which Mesh::Check then rejects with a clear message.
      std::string token;
      char* end = nullptr;
      const double value = (stream_ >> token) ? std::strtod(token.c_str(), &end) : 0.0;
      if (token.empty() || end != token.c_str() + token.size()) {
        throw std::runtime_error(std::string("truncated or malformed PLY data in ") + where);
      }
      return value;
    }
    unsigned char bytes[8];
    const std::size_t size = SizeOf(type);
    stream_.read(reinterpret_cast<char*>(bytes), static_cast<std::streamsize>(size));
    if (stream_.gcount() != static_cast<std::streamsize>(size)) {
      throw std::runtime_error(std::string("truncated PLY file: it ends inside ") + where);
    }
    if (format_ == PlyFormat::kBinaryBigEndian) std::reverse(bytes, bytes + size);
    switch (type) {
      case PlyType::kInt8: return static_cast<double>(static_cast<std::int8_t>(bytes[0]));
      case PlyType::kUInt8: return bytes[0];
      case PlyType::kInt16: return Decode<std::int16_t>(bytes);
      case PlyType::kUInt16: return Decode<std::uint16_t>(bytes);
      case PlyType::kInt32: return Decode<std::int32_t>(bytes);
      case PlyType::kUInt32: return Decode<std::uint32_t>(bytes);
      case PlyType::kFloat32: return Decode<float>(bytes);
      case PlyType::kFloat64: return Decode<double>(bytes);
    }
    return 0.0;
  }

 private:
  template <typename T>
  static double Decode(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return static_cast<double>(value);
  }
  std::istream& stream_;
  PlyFormat format_;
};

// The header: format and elements in order.
PlyFormat ReadHeader(std::istream& stream, std::vector<PlyElement>* elements) {
  std::string line;
  if (!std::getline(stream, line) || line.rfind("ply", 0) != 0) throw std::runtime_error("not a PLY file (no 'ply' magic)");
  PlyFormat format = PlyFormat::kAscii;
  bool have_format = false;
  while (std::getline(stream, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream fields(line);
    std::string keyword;
    fields >> keyword;
    if (keyword == "end_header") {
      if (!have_format) throw std::runtime_error("PLY header has no format line");
      return format;
    }
    if (keyword == "format") {
      std::string name;
      fields >> name;
      if (name == "ascii") format = PlyFormat::kAscii;
      else if (name == "binary_little_endian") format = PlyFormat::kBinaryLittleEndian;
      else if (name == "binary_big_endian") format = PlyFormat::kBinaryBigEndian;
      else throw std::runtime_error("PLY header: unknown format '" + name + "'");
      have_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      long long count = -1;
      fields >> element.name >> count;
      if (count < 0) throw std::runtime_error("PLY header: element '" + element.name + "' has no valid count");
      element.count = static_cast<std::size_t>(count);
      elements->push_back(element);
    } else if (keyword == "property") {
      if (elements->empty()) throw std::runtime_error("PLY header: property before any element");
      PlyProperty property;
      std::string type;
      fields >> type;
      if (type == "list") {
        std::string count_type, item_type;
        fields >> count_type >> item_type;
        property.is_list = true;
        property.count_type = ParseType(count_type);
        property.type = ParseType(item_type);
      } else {
        property.type = ParseType(type);
      }
      fields >> property.name;
      elements->back().properties.push_back(property);
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      throw std::runtime_error("PLY header: unexpected line '" + line + "'");
    }
  }
  throw std::runtime_error("PLY header has no end_header line");
}

// One record of an element: scalar properties as doubles, list properties as vectors.
struct Record {
  std::vector<double> scalars;
  std::vector<std::vector<double>> lists;
};

void ReadRecord(ValueReader& reader, const PlyElement& element, Record* record) {
  record->scalars.assign(element.properties.size(), 0.0);
  record->lists.resize(element.properties.size());
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    const std::string where = element.name + " " + property.name;
    if (!property.is_list) {
      record->scalars[p] = reader.Read(property.type, where.c_str());
      continue;
    }
    const double count = reader.Read(property.count_type, where.c_str());
    // Negated so that a NaN length (a float count type) fails too: it has no size_t.
    if (!(count >= 0 && count <= 1024) || count != std::floor(count)) {
      throw std::runtime_error("PLY " + where + " has an implausible list length");
    }
    record->lists[p].resize(static_cast<std::size_t>(count));
    for (double& value : record->lists[p]) value = reader.Read(property.type, where.c_str());
  }
}

// A colour channel as a byte, clamped to [0, 255]. NaN (a float colour of a damaged file) has no byte.
std::uint8_t ColourByte(double value, const char* element) {
  if (std::isnan(value)) throw std::runtime_error(std::string("PLY ") + element + " colour is not a number");
  return static_cast<std::uint8_t>(std::clamp(value, 0.0, 255.0));
}

int FindFirst(const PlyElement& element, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    if (const int index = element.Find(name); index >= 0) return index;
  }
  return -1;
}

}  // namespace

Mesh ReadPly(std::istream& stream) {
  std::vector<PlyElement> elements;
  const PlyFormat format = ReadHeader(stream, &elements);
  ValueReader reader(stream, format);
  Mesh mesh;
  Record record;
  for (const PlyElement& element : elements) {
    if (element.name == "vertex") {
      const int x = element.Find("x"), y = element.Find("y"), z = element.Find("z");
      if (x < 0 || y < 0 || z < 0) throw std::runtime_error("PLY vertices lack x, y or z");
      const int red = element.Find("red"), green = element.Find("green"), blue = element.Find("blue");
      const bool colours = red >= 0 && green >= 0 && blue >= 0;
      const int u = FindFirst(element, {"s", "u", "texture_u"}), v = FindFirst(element, {"t", "v", "texture_v"});
      const bool texcoords = u >= 0 && v >= 0;
      const int nx = element.Find("nx"), ny = element.Find("ny"), nz = element.Find("nz");
      const bool normals = nx >= 0 && ny >= 0 && nz >= 0;
      mesh.vertices.reserve(std::min<std::size_t>(element.count, 1u << 24));
      for (std::size_t i = 0; i < element.count; ++i) {
        ReadRecord(reader, element, &record);
        mesh.vertices.emplace_back(record.scalars[x], record.scalars[y], record.scalars[z]);
        if (colours) {
          const bool unit = element.properties[red].type == PlyType::kFloat32 ||
                            element.properties[red].type == PlyType::kFloat64;
          Eigen::Matrix<std::uint8_t, 3, 1> colour;
          int c = 0;
          for (int channel : {red, green, blue}) {
            const double value = unit ? 255.0 * record.scalars[channel] + 0.5 : record.scalars[channel];
            colour[c++] = ColourByte(value, "vertex");
          }
          mesh.vertex_colors.push_back(colour);
        }
        if (normals) {
          mesh.vertex_normals.push_back(
              Eigen::Vector3d(record.scalars[nx], record.scalars[ny], record.scalars[nz]).normalized().cast<float>());
        }
        if (texcoords) {
          mesh.vertex_texcoords.emplace_back(static_cast<float>(record.scalars[u]), static_cast<float>(record.scalars[v]));
        }
      }
    } else if (element.name == "face") {
      const int indices = FindFirst(element, {"vertex_indices", "vertex_index"});
      if (indices < 0 || !element.properties[indices].is_list) {
        throw std::runtime_error("PLY faces lack a vertex_indices (or vertex_index) list");
      }
      const int texcoord = element.Find("texcoord");
      const int red = element.Find("red"), green = element.Find("green"), blue = element.Find("blue");
      const bool colours = red >= 0 && green >= 0 && blue >= 0;
      // Triangles, one a face (polygons add more): a vector grown by doubling would hold up to twice that.
      mesh.faces.reserve(std::min<std::size_t>(element.count, 1u << 24));
      for (std::size_t f = 0; f < element.count; ++f) {
        ReadRecord(reader, element, &record);
        const std::vector<double>& corners = record.lists[indices];
        if (corners.size() < 3) throw std::runtime_error("PLY face " + std::to_string(f) + " has fewer than 3 vertices");
        for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
          Mesh::Face face;
          const std::size_t fan[3] = {0, k, k + 1};
          for (int c = 0; c < 3; ++c) {
            const double index = corners[fan[c]];
            if (!(index >= 0 && index < 4294967295.0)) {  // NaN too (an ASCII file may say "nan")
              throw std::runtime_error("PLY face " + std::to_string(f) + " has a negative, huge or NaN vertex index");
            }
            face[c] = static_cast<std::uint32_t>(index);
          }
          mesh.faces.push_back(face);
          if (colours) {
            mesh.face_colors.emplace_back(ColourByte(record.scalars[red], "face"),
                                          ColourByte(record.scalars[green], "face"),
                                          ColourByte(record.scalars[blue], "face"));
          }
          if (texcoord >= 0 && record.lists[texcoord].size() == 2 * corners.size()) {
            std::array<Eigen::Vector2f, 3> uv;
            for (int c = 0; c < 3; ++c) {
              uv[c] = Eigen::Vector2f(static_cast<float>(record.lists[texcoord][2 * fan[c]]),
                                      static_cast<float>(record.lists[texcoord][2 * fan[c] + 1]));
            }
            mesh.corner_texcoords.push_back(uv);
          }
        }
      }
      if (!mesh.corner_texcoords.empty() && mesh.corner_texcoords.size() != mesh.faces.size()) {
        throw std::runtime_error("PLY face texcoord lists do not match their vertex lists");
      }
    } else if (!element.properties.empty()) {  // records without properties hold no bytes, whatever their count
      for (std::size_t i = 0; i < element.count; ++i) ReadRecord(reader, element, &record);
    }
  }
  // More data than the header declares: a wrong count (faces dropped silently) or a damaged file.
  if (format == PlyFormat::kAscii) stream >> std::ws;
  if (stream.peek() != std::istream::traits_type::eof()) {
    throw std::runtime_error("the PLY file holds more data than its header declares (" +
                             std::to_string(mesh.vertices.size()) + " vertices, " + std::to_string(mesh.faces.size()) +
                             " faces read)");
  }
  return mesh;
}

void WritePly(const Mesh& mesh, std::ostream& stream, const std::vector<std::string>& comments) {
  const bool colours = !mesh.vertex_colors.empty();
  const bool texcoords = !mesh.vertex_texcoords.empty();
  const bool corners = !mesh.corner_texcoords.empty();
  const bool normals = !mesh.vertex_normals.empty();
  const bool face_colours = !mesh.face_colors.empty();
  stream << "ply\nformat binary_little_endian 1.0\ncomment written by lutex\n";
  for (const std::string& comment : comments) stream << "comment " << comment << "\n";
  stream << "element vertex " << mesh.vertices.size() << "\n"
         << "property double x\nproperty double y\nproperty double z\n";
  if (normals) stream << "property float nx\nproperty float ny\nproperty float nz\n";
  if (colours) stream << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (texcoords) stream << "property float s\nproperty float t\n";
  stream << "element face " << mesh.faces.size() << "\nproperty list uchar int vertex_indices\n";
  if (corners) stream << "property list uchar float texcoord\n";
  if (face_colours) stream << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  stream << "end_header\n";
  const auto put = [&stream](const auto& value) {
    stream.write(reinterpret_cast<const char*>(&value), sizeof(value));
  };
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) put(mesh.vertices[i][k]);
    if (normals) for (int k = 0; k < 3; ++k) put(mesh.vertex_normals[i][k]);
    if (colours) for (int k = 0; k < 3; ++k) put(mesh.vertex_colors[i][k]);
    if (texcoords) for (int k = 0; k < 2; ++k) put(mesh.vertex_texcoords[i][k]);
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    put(std::uint8_t{3});
    for (std::uint32_t index : mesh.faces[f]) put(static_cast<std::int32_t>(index));
    if (corners) {
      put(std::uint8_t{6});
      for (const Eigen::Vector2f& uv : mesh.corner_texcoords[f]) {
        put(uv.x());
        put(uv.y());
      }
    }
    if (face_colours) for (int k = 0; k < 3; ++k) put(mesh.face_colors[f][k]);
  }
}

}  // namespace lutex
