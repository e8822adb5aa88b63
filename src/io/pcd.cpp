#include "litamin2/io/pcd.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "litamin2/io/file_util.hpp"
#include "litamin2/io/io_error.hpp"

#include <liblzf/lzf.h>

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "litamin2::io reads and writes little-endian binary files and assumes a little-endian host"
#endif

namespace litamin2::io {

namespace {

struct Field {
  std::string name;
  std::size_t size = 4;
  char type = 'F';
  std::size_t count = 1;
  std::size_t offset = 0;  ///< byte offset in a binary record
  std::size_t column = 0;  ///< first token index in an ASCII line
};

struct Header {
  std::vector<Field> fields;
  std::size_t width = 0;
  std::size_t height = 1;
  std::optional<std::size_t> points;
  std::string data;
  std::size_t data_offset = 0;  ///< first byte after the DATA line
  std::size_t record_size = 0;
  std::size_t tokens_per_point = 0;
};

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::size_t parse_count(const std::string& path, std::size_t line_no, std::string_view key,
                        std::string_view token) {
  const auto value = parse_unsigned(token);
  if (!value) {
    const std::string where =
        line_no > 0 ? "header line " + std::to_string(line_no) + ": " : std::string("header: ");
    throw IoError(path, where + std::string(key) + " value '" + std::string(token) +
                            "' is not a non-negative integer");
  }
  return static_cast<std::size_t>(*value);
}

Header parse_header(const std::string& path, const std::string& bytes) {
  Header header;
  std::vector<std::string_view> sizes, types, counts;
  bool have_fields = false, have_width = false;
  std::size_t pos = 0;
  std::size_t line_no = 0;
  while (true) {
    if (pos >= bytes.size()) {
      throw IoError(path, "no DATA line: not a PCD file, or its header is truncated");
    }
    std::size_t end = bytes.find('\n', pos);
    const bool last = end == std::string::npos;
    if (last) end = bytes.size();
    std::string_view line(bytes.data() + pos, end - pos);
    pos = last ? bytes.size() : end + 1;
    ++line_no;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    const auto tokens = split_whitespace(line);
    if (tokens.empty()) continue;
    const std::string key = upper(tokens[0]);
    const std::vector<std::string_view> values(tokens.begin() + 1, tokens.end());
    const std::string where = "header line " + std::to_string(line_no) + ": ";
    if (key == "VERSION" || key == "VIEWPOINT") {
      continue;
    } else if (key == "FIELDS" || key == "COLUMNS") {
      header.fields.clear();
      for (auto name : values) header.fields.push_back(Field{std::string(name)});
      have_fields = true;
    } else if (key == "SIZE") {
      sizes = values;
    } else if (key == "TYPE") {
      types = values;
    } else if (key == "COUNT") {
      counts = values;
    } else if (key == "WIDTH") {
      if (values.size() != 1) throw IoError(path, where + "WIDTH needs one value");
      header.width = parse_count(path, line_no, key, values[0]);
      have_width = true;
    } else if (key == "HEIGHT") {
      if (values.size() != 1) throw IoError(path, where + "HEIGHT needs one value");
      header.height = parse_count(path, line_no, key, values[0]);
    } else if (key == "POINTS") {
      if (values.size() != 1) throw IoError(path, where + "POINTS needs one value");
      header.points = parse_count(path, line_no, key, values[0]);
    } else if (key == "DATA") {
      if (values.size() != 1) throw IoError(path, where + "DATA needs one value");
      header.data = std::string(values[0]);
      header.data_offset = pos;
      break;
    } else {
      throw IoError(path, where + "unexpected header entry '" + std::string(tokens[0]) +
                              "' (not a PCD file?)");
    }
  }

  if (header.data != "ascii" && header.data != "binary" && header.data != "binary_compressed") {
    throw IoError(path, "unknown DATA type '" + header.data +
                            "' (expected ascii, binary or binary_compressed)");
  }
  if (!have_fields || header.fields.empty()) throw IoError(path, "header has no FIELDS line");
  if (!have_width) throw IoError(path, "header has no WIDTH line");
  const std::size_t n_fields = header.fields.size();
  auto check_len = [&](const std::vector<std::string_view>& v, const char* key, bool required) {
    if (v.empty() && !required) return;
    if (v.size() != n_fields) {
      throw IoError(path, std::string(key) + " has " + std::to_string(v.size()) +
                              " entries but FIELDS has " + std::to_string(n_fields));
    }
  };
  check_len(sizes, "SIZE", true);
  check_len(types, "TYPE", true);
  check_len(counts, "COUNT", false);

  constexpr std::size_t kMaxRecord = std::size_t{1} << 20;
  for (std::size_t i = 0; i < n_fields; ++i) {
    Field& f = header.fields[i];
    f.size = parse_count(path, 0, "SIZE", sizes[i]);
    const std::string type = upper(types[i]);
    if (type.size() != 1 || (type[0] != 'F' && type[0] != 'U' && type[0] != 'I')) {
      throw IoError(path, "field '" + f.name + "' has unknown TYPE '" + std::string(types[i]) +
                              "' (expected F, U or I)");
    }
    f.type = type[0];
    if (f.size != 1 && f.size != 2 && f.size != 4 && f.size != 8) {
      throw IoError(path, "field '" + f.name + "' has invalid SIZE " + std::to_string(f.size));
    }
    if (f.type == 'F' && f.size != 4 && f.size != 8) {
      throw IoError(path, "field '" + f.name + "' has TYPE F with SIZE " + std::to_string(f.size) +
                              " (expected 4 or 8)");
    }
    f.count = counts.empty() ? 1 : parse_count(path, 0, "COUNT", counts[i]);
    if (f.count == 0 || f.count > kMaxRecord) {
      throw IoError(path, "field '" + f.name + "' has invalid COUNT " + std::to_string(f.count));
    }
    f.offset = header.record_size;
    f.column = header.tokens_per_point;
    header.record_size += f.size * f.count;
    header.tokens_per_point += f.count;
    if (header.record_size > kMaxRecord) throw IoError(path, "point record size is implausible");
  }

  const std::size_t max_dim = std::size_t{1} << 31;
  if (header.width > max_dim || header.height > max_dim) {
    throw IoError(path, "WIDTH/HEIGHT are implausibly large");
  }
  const std::size_t wh = header.width * header.height;
  if (!header.points) header.points = wh;
  if (*header.points != wh) {
    throw IoError(path, "WIDTH*HEIGHT = " + std::to_string(header.width) + "*" +
                            std::to_string(header.height) + " = " + std::to_string(wh) +
                            " but POINTS = " + std::to_string(*header.points));
  }
  return header;
}

const Field* find_field(const std::string& path, const Header& header, const std::string& name,
                        bool required) {
  for (const Field& f : header.fields) {
    if (f.name != name) continue;
    if (f.count != 1) {
      throw IoError(path,
                    "field '" + name + "' has COUNT " + std::to_string(f.count) + ", expected 1");
    }
    return &f;
  }
  if (required) throw IoError(path, "required field '" + name + "' is missing from FIELDS");
  return nullptr;
}

template <typename T>
double load(const char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return static_cast<double>(value);
}

/// Decodes one binary value of a field at `p`.
double decode(const Field& f, const char* p) {
  switch (f.type) {
    case 'F':
      return f.size == 4 ? load<float>(p) : load<double>(p);
    case 'U':
      switch (f.size) {
        case 1:
          return load<std::uint8_t>(p);
        case 2:
          return load<std::uint16_t>(p);
        case 4:
          return load<std::uint32_t>(p);
        default:
          return load<std::uint64_t>(p);
      }
    default:
      switch (f.size) {
        case 1:
          return load<std::int8_t>(p);
        case 2:
          return load<std::int16_t>(p);
        case 4:
          return load<std::int32_t>(p);
        default:
          return load<std::int64_t>(p);
      }
  }
}

/// Appends point `index` of the file: dropped when a coordinate is NaN/Inf (PCL's "no return"
/// points of organised clouds); a coordinate beyond float range or an intensity that is not a
/// finite float rejects the file (IoError): nothing is repaired.
void append_point(const std::string& path, std::size_t index, PointCloud& cloud,
                  const Eigen::Vector3d& p, const Field* intensity_field, double intensity,
                  const Field* time_field, double time, std::vector<double>& times) {
  if (!p.allFinite()) return;
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  if (p.cwiseAbs().maxCoeff() > kFloatMax)
    throw IoError(path, "point " + std::to_string(index) + ": a coordinate is beyond float range");
  cloud.points.push_back(p.cast<float>());
  if (time_field) times.push_back(time);  // checked with the others (relative_times)
  if (!intensity_field) return;
  if (!(std::fabs(intensity) <= kFloatMax))
    throw IoError(path, "point " + std::to_string(index) + ": intensity " +
                            std::to_string(intensity) + " is not a finite float");
  cloud.intensities.push_back(static_cast<float>(intensity));
}

/// Per-point time fields as LiDAR drivers write them, in the order one is chosen when a file has
/// several: Ouster's t, Velodyne's time, Hesai's timestamp, Livox's offset_time.
constexpr const char* kTimeFields[] = {"t", "time", "timestamp", "offset_time"};

/// The first per-point time field of kTimeFields in the file, or null.
const Field* find_time_field(const std::string& path, const Header& header) {
  for (const char* name : kTimeFields) {
    if (const Field* f = find_field(path, header, name, false)) return f;
  }
  return nullptr;
}

/// The raw values of a time field as seconds relative to the sweep (PointCloud::times): integer
/// fields are nanoseconds, float fields seconds; times within +-kMaxPointTime are relative (to
/// the scan's stamp), larger ones absolute and taken relative to the scan's earliest point, the
/// sweep start (a PCD has no stamp). Throws IoError for a non-finite time, absolute times in a
/// float32 field (its 24 bits cannot resolve them) and a span beyond kMaxPointTime.
std::vector<float> relative_times(const std::string& path, const Field& field,
                                  const std::vector<double>& raw) {
  const double unit = field.type == 'F' ? 1.0 : 1e-9;
  const std::string who = "time field '" + field.name + "' (TYPE " + std::string(1, field.type) +
                          " SIZE " + std::to_string(field.size) + ", " +
                          (field.type == 'F' ? "seconds" : "nanoseconds") + ")";
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (!std::isfinite(raw[i]))
      throw IoError(path, who + ": point " + std::to_string(i) + " has a non-finite time");
    const double t = raw[i] * unit;
    lo = i == 0 ? t : std::min(lo, t);
    hi = i == 0 ? t : std::max(hi, t);
  }
  const bool relative = std::max(std::abs(lo), std::abs(hi)) <= kMaxPointTime;
  if (!relative && field.type == 'F' && field.size == 4)
    throw IoError(path, who + ": values up to " + std::to_string(hi) +
                            " s are absolute times, which float32 cannot resolve");
  if (hi - lo > kMaxPointTime)
    throw IoError(path, who + ": the times span " + std::to_string(hi - lo) +
                            " s, more than a sweep (at most 1 s)");
  std::vector<float> times(raw.size());
  const double origin = relative ? 0.0 : lo;
  for (std::size_t i = 0; i < raw.size(); ++i)
    times[i] = static_cast<float>(raw[i] * unit - origin);
  return times;
}

/// The uncompressed point data of a DATA binary_compressed file (PCL's layout): after the DATA
/// line, the compressed and the uncompressed size (uint32 little-endian each), then that many
/// bytes of LZF data (liblzf, as PCL writes it). The uncompressed size must be POINTS times the
/// record size; sizes that no LZF stream can produce (more than 88 output bytes per input byte,
/// its longest back-reference: 264 bytes in 3) are rejected before any allocation, so a small
/// file cannot claim gigabytes. Throws IoError for a truncated or corrupt stream.
std::string decompress_lzf(const std::string& path, const Header& header,
                           const std::string& bytes) {
  const std::size_t available = bytes.size() - header.data_offset;
  if (available < 8) throw IoError(path, "binary_compressed: truncated before the two size words");
  std::uint32_t compressed_size = 0, uncompressed_size = 0;
  std::memcpy(&compressed_size, bytes.data() + header.data_offset, 4);
  std::memcpy(&uncompressed_size, bytes.data() + header.data_offset + 4, 4);
  const std::size_t n = *header.points;
  if (n > std::numeric_limits<std::uint32_t>::max() / header.record_size ||
      uncompressed_size != n * header.record_size) {
    throw IoError(path, "binary_compressed: the uncompressed size " +
                            std::to_string(uncompressed_size) + " is not POINTS " +
                            std::to_string(n) + " x " + std::to_string(header.record_size) +
                            " bytes");
  }
  if (compressed_size > available - 8) {
    throw IoError(path, "binary_compressed: " + std::to_string(compressed_size) +
                            " compressed bytes announced, only " + std::to_string(available - 8) +
                            " present (truncated)");
  }
  constexpr std::size_t kLzfMaxExpansion = 88;
  if (uncompressed_size > std::size_t{compressed_size} * kLzfMaxExpansion) {
    throw IoError(path, "binary_compressed: " + std::to_string(compressed_size) +
                            " compressed bytes cannot hold " + std::to_string(uncompressed_size) +
                            " bytes of LZF data (corrupt sizes)");
  }
  std::string out(uncompressed_size, '\0');
  if (uncompressed_size == 0) return out;
  const unsigned int got = lzf_decompress(bytes.data() + header.data_offset + 8, compressed_size,
                                          out.data(), uncompressed_size);
  if (got != uncompressed_size) {
    throw IoError(path, "binary_compressed: the LZF data is corrupt (" + std::to_string(got) +
                            " of " + std::to_string(uncompressed_size) + " bytes decoded)");
  }
  return out;
}

}  // namespace

PointCloud read_pcd(const std::string& path) {
  const std::string bytes = read_file_bytes(path);
  const Header header = parse_header(path, bytes);
  const Field* fx = find_field(path, header, "x", true);
  const Field* fy = find_field(path, header, "y", true);
  const Field* fz = find_field(path, header, "z", true);
  for (const Field* f : {fx, fy, fz}) {
    if (f->type != 'F') {
      throw IoError(path, "field '" + f->name + "' has TYPE " + std::string(1, f->type) +
                              ", expected F (float)");
    }
  }
  const Field* fi = find_field(path, header, "intensity", false);
  const Field* ft = find_time_field(path, header);
  const std::size_t n = *header.points;
  PointCloud cloud;
  std::vector<double> raw_times;
  // The cloud with its times, once every point is read.
  auto finish = [&]() {
    if (ft) cloud.times = relative_times(path, *ft, raw_times);
    return cloud;
  };

  if (header.data != "ascii") {
    // Binary records are interleaved (AoS): point i's field f at i * record_size + f.offset.
    // binary_compressed holds the same bytes field by field (SoA), so field f's block starts
    // at n * f.offset and point i's value at block + i * f.size * f.count.
    const bool compressed = header.data == "binary_compressed";
    const std::string payload = compressed ? decompress_lzf(path, header, bytes) : std::string();
    const char* base = compressed ? payload.data() : bytes.data() + header.data_offset;
    if (!compressed) {
      const std::size_t available = bytes.size() - header.data_offset;
      if (n > available / header.record_size) {
        throw IoError(path, "truncated binary data: " + std::to_string(n) + " points of " +
                                std::to_string(header.record_size) + " bytes need " +
                                std::to_string(n * header.record_size) + " bytes, only " +
                                std::to_string(available) + " present");
      }
    }
    const auto at = [&](const Field& f, std::size_t i) {
      return compressed ? base + n * f.offset + i * f.size * f.count
                        : base + i * header.record_size + f.offset;
    };
    cloud.points.reserve(n);
    if (fi) cloud.intensities.reserve(n);
    if (ft) raw_times.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d p(decode(*fx, at(*fx, i)), decode(*fy, at(*fy, i)),
                              decode(*fz, at(*fz, i)));
      append_point(path, i, cloud, p, fi, fi ? decode(*fi, at(*fi, i)) : 0.0, ft,
                   ft ? decode(*ft, at(*ft, i)) : 0.0, raw_times);
    }
    return finish();
  }

  // ASCII: one point per non-blank line.
  const std::string_view text(bytes.data() + header.data_offset, bytes.size() - header.data_offset);
  const auto lines = split_lines(text);
  std::size_t read = 0;
  std::size_t header_lines = 0;
  for (std::size_t k = 0; k < header.data_offset; ++k) header_lines += bytes[k] == '\n';
  cloud.points.reserve(std::min(n, lines.size()));
  for (std::size_t li = 0; li < lines.size(); ++li) {
    if (is_blank(lines[li])) continue;
    const std::size_t line_no = header_lines + li + 1;
    if (read == n) {
      throw IoError(path, "line " + std::to_string(line_no) + ": more data lines than POINTS " +
                              std::to_string(n));
    }
    const auto tokens = split_whitespace(lines[li]);
    if (tokens.size() != header.tokens_per_point) {
      throw IoError(path, "line " + std::to_string(line_no) + ": " + std::to_string(tokens.size()) +
                              " values, expected " + std::to_string(header.tokens_per_point));
    }
    auto value = [&](const Field* f) {
      const auto v = parse_double(tokens[f->column]);
      if (!v) {
        throw IoError(path, "line " + std::to_string(line_no) + ": field '" + f->name +
                                "' value '" + std::string(tokens[f->column]) + "' is not a number");
      }
      return *v;
    };
    append_point(path, read, cloud, Eigen::Vector3d(value(fx), value(fy), value(fz)), fi,
                 fi ? value(fi) : 0.0, ft, ft ? value(ft) : 0.0, raw_times);
    ++read;
  }
  if (read != n) {
    throw IoError(path, "truncated ASCII data: " + std::to_string(read) + " of " +
                            std::to_string(n) + " points present");
  }
  return finish();
}

void write_pcd_binary(const std::string& path, const PointCloud& cloud) {
  write_pcd_binary(path, cloud, {});
}

namespace {

/// Stores `value` as a PCD field of the given type and size at `dst`.
void encode(const PcdField& f, double value, char* dst) {
  auto store = [&](auto v) { std::memcpy(dst, &v, sizeof(v)); };
  auto integer = [&](double lo, double hi) { return std::clamp(std::round(value), lo, hi); };
  if (f.type == 'F') {
    if (f.size == 4) return store(static_cast<float>(value));
    return store(value);
  }
  if (f.type == 'U') {
    if (f.size == 1) return store(static_cast<std::uint8_t>(integer(0, 255)));
    if (f.size == 2) return store(static_cast<std::uint16_t>(integer(0, 65535)));
    return store(static_cast<std::uint32_t>(integer(0, 4294967295.0)));
  }
  if (f.size == 1) return store(static_cast<std::int8_t>(integer(-128, 127)));
  if (f.size == 2) return store(static_cast<std::int16_t>(integer(-32768, 32767)));
  store(static_cast<std::int32_t>(integer(-2147483648.0, 2147483647.0)));
}

void check_field(const std::string& path, const PcdField& f, std::size_t points,
                 const std::vector<std::string>& taken) {
  const std::string who = "write_pcd_binary(" + path + "): field '" + f.name + "': ";
  if (f.name.empty() || std::any_of(f.name.begin(), f.name.end(), [](char c) {
        return std::isspace(static_cast<unsigned char>(c)) != 0;
      })) {
    throw std::invalid_argument(who + "name must be non-empty without white space");
  }
  if (std::find(taken.begin(), taken.end(), f.name) != taken.end()) {
    throw std::invalid_argument(who + "name is used twice");
  }
  const bool ok = f.type == 'F'                      ? (f.size == 4 || f.size == 8)
                  : (f.type == 'U' || f.type == 'I') ? (f.size == 1 || f.size == 2 || f.size == 4)
                                                     : false;
  if (!ok) {
    throw std::invalid_argument(who + "TYPE " + std::string(1, f.type) + " with SIZE " +
                                std::to_string(f.size) + " is not supported");
  }
  if (f.values.size() != points) {
    throw std::invalid_argument(who + std::to_string(f.values.size()) + " values for " +
                                std::to_string(points) + " points");
  }
}

}  // namespace

void write_pcd_binary(const std::string& path, const PointCloud& cloud,
                      const std::vector<PcdField>& extra) {
  if (cloud.has_intensities() && cloud.intensities.size() != cloud.points.size()) {
    throw std::invalid_argument(
        "write_pcd_binary(" + path + "): " + std::to_string(cloud.intensities.size()) +
        " intensities for " + std::to_string(cloud.points.size()) + " points");
  }
  const bool with_i = cloud.has_intensities();
  const std::size_t n = cloud.points.size();
  std::vector<std::string> taken = {"x", "y", "z"};
  if (with_i) taken.push_back("intensity");
  for (const PcdField& f : extra) {
    check_field(path, f, n, taken);
    taken.push_back(f.name);
  }
  std::string fields = "FIELDS x y z", sizes = "SIZE 4 4 4", types = "TYPE F F F",
              counts = "COUNT 1 1 1";
  std::size_t stride = 3 * sizeof(float);
  if (with_i) {
    fields += " intensity";
    sizes += " 4";
    types += " F";
    counts += " 1";
    stride += sizeof(float);
  }
  for (const PcdField& f : extra) {
    fields += " " + f.name;
    sizes += " " + std::to_string(f.size);
    types += " " + std::string(1, f.type);
    counts += " 1";
    stride += f.size;
  }
  std::string out = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n";
  out += fields + "\n" + sizes + "\n" + types + "\n" + counts + "\n";
  out += "WIDTH " + std::to_string(n) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(n) + "\nDATA binary\n";
  const std::size_t header_size = out.size();
  out.resize(header_size + n * stride);
  char* dst = out.data() + header_size;
  for (std::size_t i = 0; i < n; ++i) {
    char* rec = dst + i * stride;
    const float xyzi[4] = {cloud.points[i].x(), cloud.points[i].y(), cloud.points[i].z(),
                           with_i ? cloud.intensities[i] : 0.0f};
    const std::size_t head = (with_i ? 4 : 3) * sizeof(float);
    std::memcpy(rec, xyzi, head);
    std::size_t offset = head;
    for (const PcdField& f : extra) {
      encode(f, f.values[i], rec + offset);
      offset += f.size;
    }
  }
  write_file_bytes(path, out.data(), out.size());
}

}  // namespace litamin2::io
