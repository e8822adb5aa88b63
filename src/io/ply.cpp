#include "litamin2/io/ply.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string_view>

#include "litamin2/io/file_util.hpp"
#include "litamin2/io/io_error.hpp"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "litamin2::io reads and writes little-endian binary files and assumes a little-endian host"
#endif

namespace litamin2::io {

namespace {

enum class Format { kAscii, kBinaryLE, kBinaryBE };

struct Property {
  std::string name;
  bool is_list = false;
  std::string type;        ///< scalar type, or item type of a list
  std::string count_type;  ///< list count type
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

/// Byte size of a PLY scalar type name, 0 if unknown.
std::size_t type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

template <typename T>
double load(const char* p, bool swap) {
  char buf[sizeof(T)];
  std::memcpy(buf, p, sizeof(T));
  if (swap) std::reverse(buf, buf + sizeof(T));
  T value;
  std::memcpy(&value, buf, sizeof(T));
  return static_cast<double>(value);
}

double decode(const std::string& t, const char* p, bool swap) {
  if (t == "char" || t == "int8") return load<std::int8_t>(p, swap);
  if (t == "uchar" || t == "uint8") return load<std::uint8_t>(p, swap);
  if (t == "short" || t == "int16") return load<std::int16_t>(p, swap);
  if (t == "ushort" || t == "uint16") return load<std::uint16_t>(p, swap);
  if (t == "int" || t == "int32") return load<std::int32_t>(p, swap);
  if (t == "uint" || t == "uint32") return load<std::uint32_t>(p, swap);
  if (t == "float" || t == "float32") return load<float>(p, swap);
  return load<double>(p, swap);
}

void validate_names(const std::string& path, const std::vector<std::string>& names) {
  if (names.empty()) throw std::invalid_argument("write_ply_vertices(" + path + "): no properties");
  std::set<std::string> seen;
  for (const std::string& name : names) {
    const auto tokens = split_whitespace(name);
    if (tokens.size() != 1 || tokens[0].size() != name.size()) {
      throw std::invalid_argument("write_ply_vertices(" + path + "): invalid property name '" +
                                  name + "'");
    }
    if (!seen.insert(name).second) {
      throw std::invalid_argument("write_ply_vertices(" + path + "): duplicate property name '" +
                                  name + "'");
    }
  }
}

}  // namespace

void write_ply_vertices(const std::string& path, const std::vector<std::string>& property_names,
                        const std::vector<float>& values_row_major) {
  validate_names(path, property_names);
  if (values_row_major.size() % property_names.size() != 0) {
    throw std::invalid_argument(
        "write_ply_vertices(" + path + "): " + std::to_string(values_row_major.size()) +
        " values is not a multiple of " + std::to_string(property_names.size()) + " properties");
  }
  const std::size_t n = values_row_major.size() / property_names.size();
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by litamin2\n";
  out += "element vertex " + std::to_string(n) + "\n";
  for (const std::string& name : property_names) out += "property float " + name + "\n";
  out += "end_header\n";
  const std::size_t header_size = out.size();
  out.resize(header_size + values_row_major.size() * sizeof(float));
  if (!values_row_major.empty()) {
    std::memcpy(out.data() + header_size, values_row_major.data(),
                values_row_major.size() * sizeof(float));
  }
  write_file_bytes(path, out.data(), out.size());
}

void write_ply_points(const std::string& path, const PointCloud& cloud) {
  if (cloud.has_intensities() && cloud.intensities.size() != cloud.points.size()) {
    throw std::invalid_argument(
        "write_ply_points(" + path + "): " + std::to_string(cloud.intensities.size()) +
        " intensities for " + std::to_string(cloud.points.size()) + " points");
  }
  const bool with_i = cloud.has_intensities();
  std::vector<std::string> names = {"x", "y", "z"};
  if (with_i) names.push_back("intensity");
  std::vector<float> values;
  values.reserve(cloud.points.size() * names.size());
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    values.insert(values.end(), {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z()});
    if (with_i) values.push_back(cloud.intensities[i]);
  }
  write_ply_vertices(path, names, values);
}

PlyVertices read_ply_vertices(const std::string& path) {
  const std::string bytes = read_file_bytes(path);
  // Header: text lines up to "end_header".
  std::size_t pos = 0;
  std::size_t line_no = 0;
  std::optional<Format> format;
  std::vector<Element> elements;
  bool ended = false;
  while (pos < bytes.size() && !ended) {
    std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    std::string_view line(bytes.data() + pos, end - pos);
    pos = std::min(bytes.size(), end + 1);
    ++line_no;
    const auto tokens = split_whitespace(line);
    const std::string where = "header line " + std::to_string(line_no) + ": ";
    if (line_no == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply")
        throw IoError(path, "not a PLY file (no 'ply' magic)");
      continue;
    }
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      if (tokens.size() != 3) throw IoError(path, where + "malformed format line");
      if (tokens[1] == "ascii")
        format = Format::kAscii;
      else if (tokens[1] == "binary_little_endian")
        format = Format::kBinaryLE;
      else if (tokens[1] == "binary_big_endian")
        format = Format::kBinaryBE;
      else
        throw IoError(path, where + "unknown format '" + std::string(tokens[1]) + "'");
    } else if (key == "element") {
      const auto count = tokens.size() == 3 ? parse_unsigned(tokens[2]) : std::nullopt;
      if (!count) throw IoError(path, where + "malformed element line");
      elements.push_back(Element{std::string(tokens[1]), static_cast<std::size_t>(*count), {}});
    } else if (key == "property") {
      if (elements.empty()) throw IoError(path, where + "property before any element");
      Property prop;
      if (tokens.size() == 5 && tokens[1] == "list") {
        prop =
            Property{std::string(tokens[4]), true, std::string(tokens[3]), std::string(tokens[2])};
        if (type_size(prop.count_type) == 0 || prop.count_type == "float" ||
            prop.count_type == "double" || prop.count_type == "float32" ||
            prop.count_type == "float64")
          throw IoError(path, where + "invalid list count type");
      } else if (tokens.size() == 3) {
        prop = Property{std::string(tokens[2]), false, std::string(tokens[1]), ""};
      } else {
        throw IoError(path, where + "malformed property line");
      }
      if (type_size(prop.type) == 0) {
        throw IoError(path, where + "unknown property type '" + prop.type + "'");
      }
      elements.back().properties.push_back(prop);
    } else if (key == "end_header") {
      ended = true;
    } else {
      throw IoError(path, where + "unexpected header entry '" + std::string(key) + "'");
    }
  }
  if (!ended) throw IoError(path, "no end_header line: not a PLY file or truncated header");
  if (!format) throw IoError(path, "header has no format line");
  for (const Element& element : elements) {
    // Items without a property occupy no byte: a count of 2^60 would be read for ever.
    if (element.count > 0 && element.properties.empty())
      throw IoError(path, "element '" + element.name + "' has items but no property");
  }

  PlyVertices result;
  const bool swap = *format == Format::kBinaryBE;
  std::vector<std::string_view> lines;
  std::size_t line_index = 0;
  if (*format == Format::kAscii) {
    lines = split_lines(std::string_view(bytes.data() + pos, bytes.size() - pos));
  }
  auto next_ascii_tokens = [&]() {
    while (line_index < lines.size() && is_blank(lines[line_index])) ++line_index;
    if (line_index >= lines.size()) throw IoError(path, "truncated ASCII data");
    return split_whitespace(lines[line_index++]);
  };

  for (const Element& element : elements) {
    const bool is_vertex = element.name == "vertex";
    if (is_vertex) {
      for (const Property& p : element.properties) {
        if (p.is_list)
          throw IoError(path, "vertex property '" + p.name + "' is a list (unsupported)");
        result.property_names.push_back(p.name);
      }
      const std::size_t n_props = element.properties.size();
      if (n_props > 0 && element.count > (bytes.size() + 1) / n_props) {
        throw IoError(path, "truncated data: " + std::to_string(element.count) +
                                " vertices cannot fit in the file");
      }
      result.values.reserve(element.count * n_props);
    }
    for (std::size_t i = 0; i < element.count; ++i) {
      if (*format == Format::kAscii) {
        const auto tokens = next_ascii_tokens();
        std::size_t t = 0;
        for (const Property& p : element.properties) {
          std::size_t items = 1;
          if (p.is_list) {
            const auto c = t < tokens.size() ? parse_unsigned(tokens[t]) : std::nullopt;
            if (!c)
              throw IoError(
                  path, "element '" + element.name + "' " + std::to_string(i) + ": bad list count");
            items = static_cast<std::size_t>(*c);
            ++t;
          }
          if (items > tokens.size() - std::min(t, tokens.size())) {
            throw IoError(path, "element '" + element.name + "' " + std::to_string(i) +
                                    ": too few values on its line");
          }
          if (is_vertex) {
            const auto v = parse_double(tokens[t]);
            if (!v) {
              throw IoError(path, "vertex " + std::to_string(i) + ": property '" + p.name +
                                      "' value '" + std::string(tokens[t]) + "' is not a number");
            }
            result.values.push_back(*v);
          }
          t += items;
        }
        if (t != tokens.size()) {
          throw IoError(path, "element '" + element.name + "' " + std::to_string(i) +
                                  ": wrong number of values on its line");
        }
      } else {
        for (const Property& p : element.properties) {
          std::size_t items = 1;
          if (p.is_list) {
            const std::size_t cs = type_size(p.count_type);
            if (cs > bytes.size() - pos) throw IoError(path, "truncated binary data");
            const double c = decode(p.count_type, bytes.data() + pos, swap);
            if (c < 0) throw IoError(path, "negative list count");
            items = static_cast<std::size_t>(c);
            pos += cs;
          }
          const std::size_t ts = type_size(p.type);
          if (items > (bytes.size() - pos) / ts) {
            throw IoError(path, "truncated binary data in element '" + element.name + "' " +
                                    std::to_string(i) + " of " + std::to_string(element.count));
          }
          if (is_vertex) result.values.push_back(decode(p.type, bytes.data() + pos, swap));
          pos += items * ts;
        }
      }
    }
    if (is_vertex) return result;
  }
  throw IoError(path, "PLY file has no 'vertex' element");
}

PointCloud read_ply_points(const std::string& path) {
  const PlyVertices v = read_ply_vertices(path);
  const int ix = v.index_of("x"), iy = v.index_of("y"), iz = v.index_of("z");
  if (ix < 0 || iy < 0 || iz < 0) throw IoError(path, "vertex element lacks x, y or z");
  const int ii = v.index_of("intensity");
  // As read_pcd: a vertex with a NaN/Inf coordinate is dropped (no return); a coordinate
  // beyond float range or an intensity that is not a finite float rejects the file.
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  PointCloud cloud;
  cloud.points.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector3d p(v.at(i, ix), v.at(i, iy), v.at(i, iz));
    if (!p.allFinite()) continue;
    if (p.cwiseAbs().maxCoeff() > kFloatMax)
      throw IoError(path, "vertex " + std::to_string(i) + ": a coordinate is beyond float range");
    cloud.points.push_back(p.cast<float>());
    if (ii < 0) continue;
    const double intensity = v.at(i, ii);
    if (!(std::fabs(intensity) <= kFloatMax))
      throw IoError(path, "vertex " + std::to_string(i) + ": intensity " +
                              std::to_string(intensity) + " is not a finite float");
    cloud.intensities.push_back(static_cast<float>(intensity));
  }
  return cloud;
}

}  // namespace litamin2::io
