#include "litamin2/dds/pointcloud2_conversion.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "litamin2/dds/time_conversion.hpp"

namespace litamin2::dds {

namespace {

// sensor_msgs/PointField datatype codes.
constexpr std::uint8_t kInt8 = 1;
constexpr std::uint8_t kUint8 = 2;
constexpr std::uint8_t kInt16 = 3;
constexpr std::uint8_t kUint16 = 4;
constexpr std::uint8_t kInt32 = 5;
constexpr std::uint8_t kUint32 = 6;
constexpr std::uint8_t kFloat32 = 7;
constexpr std::uint8_t kFloat64 = 8;

/// Size in bytes of a datatype, 0 for an unknown code.
std::size_t datatype_size(std::uint8_t datatype) {
  switch (datatype) {
    case kInt8:
    case kUint8:
      return 1;
    case kInt16:
    case kUint16:
      return 2;
    case kInt32:
    case kUint32:
    case kFloat32:
      return 4;
    case kFloat64:
      return 8;
    default:
      return 0;
  }
}

bool host_is_big_endian() {
  const std::uint16_t probe = 1;
  std::uint8_t first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 0;
}

/// Reads a value of `Size` bytes at p (any alignment), byte-swapped if `swap`.
template <typename T>
T load(const std::uint8_t* p, bool swap) {
  std::array<std::uint8_t, sizeof(T)> bytes;
  std::memcpy(bytes.data(), p, sizeof(T));
  if (swap) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, bytes.data(), sizeof(T));
  return value;
}

/// Reads one value of a known datatype as float (doubles are rounded to float; values out of
/// float's range become +-Inf).
float read_as_float(const std::uint8_t* p, std::uint8_t datatype, bool swap) {
  switch (datatype) {
    case kInt8:
      return static_cast<float>(load<std::int8_t>(p, false));
    case kUint8:
      return static_cast<float>(load<std::uint8_t>(p, false));
    case kInt16:
      return static_cast<float>(load<std::int16_t>(p, swap));
    case kUint16:
      return static_cast<float>(load<std::uint16_t>(p, swap));
    case kInt32:
      return static_cast<float>(load<std::int32_t>(p, swap));
    case kUint32:
      return static_cast<float>(load<std::uint32_t>(p, swap));
    case kFloat32:
      return load<float>(p, swap);
    case kFloat64: {
      const double v = load<double>(p, swap);
      if (std::isfinite(v) &&
          std::fabs(v) > static_cast<double>(std::numeric_limits<float>::max())) {
        return v > 0 ? std::numeric_limits<float>::infinity()
                     : -std::numeric_limits<float>::infinity();
      }
      return static_cast<float>(v);
    }
    default:
      return 0.0f;
  }
}

/// Reads one value of a known datatype as double (exact for every PointField datatype).
double read_as_double(const std::uint8_t* p, std::uint8_t datatype, bool swap) {
  switch (datatype) {
    case kInt8:
      return load<std::int8_t>(p, false);
    case kUint8:
      return load<std::uint8_t>(p, false);
    case kInt16:
      return load<std::int16_t>(p, swap);
    case kUint16:
      return load<std::uint16_t>(p, swap);
    case kInt32:
      return load<std::int32_t>(p, swap);
    case kUint32:
      return load<std::uint32_t>(p, swap);
    case kFloat32:
      return load<float>(p, swap);
    case kFloat64:
      return load<double>(p, swap);
    default:
      return 0.0;
  }
}

/// Per-point time fields as drivers publish them, in the order one is chosen when a message
/// has several: Ouster's t, Velodyne's time, Hesai's timestamp, Livox's offset_time.
constexpr const char* kTimeFields[] = {"t", "time", "timestamp", "offset_time"};

/// A field the conversion reads.
struct FieldSpec {
  const char* name;
  bool found = false;
  std::uint32_t offset = 0;
  std::uint8_t datatype = 0;
};

/// The message's point data: its data() or, when converting from a serialised payload, the
/// bytes of the data sequence in that payload.
struct PointBytes {
  const std::uint8_t* data;
  std::size_t size;
};

}  // namespace

CloudError CloudConversion::reject(CloudError why, std::string reason) {
  error = why;
  message = std::move(reason);
  cloud.points.clear();
  cloud.intensities.clear();
  cloud.times.clear();
  return why;
}

const char* to_string(CloudError error) {
  switch (error) {
    case CloudError::kNone:
      return "none";
    case CloudError::kMissingField:
      return "missing_field";
    case CloudError::kDuplicateField:
      return "duplicate_field";
    case CloudError::kBadFieldType:
      return "bad_field_type";
    case CloudError::kFieldOutOfBounds:
      return "field_out_of_bounds";
    case CloudError::kBadRowStep:
      return "bad_row_step";
    case CloudError::kDataSizeMismatch:
      return "data_size_mismatch";
    case CloudError::kTooManyPoints:
      return "too_many_points";
    case CloudError::kBadStamp:
      return "bad_stamp";
    case CloudError::kBadTimeField:
      return "bad_time_field";
    case CloudError::kNonFiniteIntensity:
      return "non_finite_intensity";
    case CloudError::kBadFrameId:
      return "bad_frame_id";
  }
  return "unknown";
}

CloudConversion from_pointcloud2(const sensor_msgs::msg::PointCloud2& msg,
                                 const CloudConversionOptions& options) {
  CloudConversion out;
  from_pointcloud2(msg, options, out);
  return out;
}

namespace {

/// Finds x, y, z (required, FLOAT32/FLOAT64) and intensity (optional, any numeric type) in the
/// message's fields and checks that each fits in point_step.
CloudError find_fields(const sensor_msgs::msg::PointCloud2& msg, std::array<FieldSpec, 4>& specs,
                       CloudConversion& out) {
  const std::uint64_t point_step = msg.point_step();
  for (const auto& field : msg.fields()) {
    for (std::size_t k = 0; k < specs.size(); ++k) {
      FieldSpec& spec = specs[k];
      if (field.name() != spec.name) continue;
      if (spec.found) {
        return out.reject(CloudError::kDuplicateField,
                          std::string("field '") + spec.name + "' appears more than once");
      }
      spec.found = true;
      spec.offset = field.offset();
      spec.datatype = field.datatype();
      const std::size_t size = datatype_size(field.datatype());
      const bool coordinate = k < 3;
      if (size == 0 ||
          (coordinate && field.datatype() != kFloat32 && field.datatype() != kFloat64)) {
        return out.reject(CloudError::kBadFieldType,
                          std::string("field '") + spec.name + "' has datatype " +
                              std::to_string(field.datatype()) +
                              (coordinate ? " (x, y, z must be FLOAT32 (7) or FLOAT64 (8))"
                                          : " (not a PointField datatype 1..8)"));
      }
      if (field.count() == 0) {
        return out.reject(CloudError::kBadFieldType,
                          std::string("field '") + spec.name + "' has count 0");
      }
      const std::uint64_t end = static_cast<std::uint64_t>(field.offset()) +
                                static_cast<std::uint64_t>(size) * field.count();
      if (end > point_step) {
        return out.reject(CloudError::kFieldOutOfBounds,
                          std::string("field '") + spec.name + "' (offset " +
                              std::to_string(field.offset()) + ", " + std::to_string(size) + " x " +
                              std::to_string(field.count()) +
                              " bytes) does not fit in point_step " + std::to_string(point_step));
      }
    }
  }
  for (std::size_t k = 0; k < 3; ++k) {
    if (!specs[k].found) {
      return out.reject(CloudError::kMissingField, std::string("no field '") + specs[k].name + "'");
    }
  }
  return CloudError::kNone;
}

/// Checks the message's extent: rows of at least width * point_step bytes, exactly height rows
/// of data, at most options.max_points points.
CloudError check_extent(const sensor_msgs::msg::PointCloud2& msg, PointBytes bytes,
                        const CloudConversionOptions& options, CloudConversion& out) {
  const std::uint64_t width = msg.width();
  const std::uint64_t height = msg.height();
  const std::uint64_t point_step = msg.point_step();
  const std::uint64_t row_step = msg.row_step();
  // Each factor is < 2^32, so these products cannot overflow 64 bits.
  if (row_step < width * point_step) {
    return out.reject(CloudError::kBadRowStep, "row_step " + std::to_string(row_step) +
                                                   " < width " + std::to_string(width) +
                                                   " * point_step " + std::to_string(point_step));
  }
  const std::uint64_t expected = row_step * height;
  if (static_cast<std::uint64_t>(bytes.size) != expected) {
    return out.reject(CloudError::kDataSizeMismatch,
                      "data has " + std::to_string(bytes.size) + " bytes, row_step " +
                          std::to_string(row_step) + " * height " + std::to_string(height) + " = " +
                          std::to_string(expected));
  }
  const std::uint64_t total = width * height;
  if (options.max_points > 0 && total > options.max_points) {
    return out.reject(CloudError::kTooManyPoints, std::to_string(total) + " points > limit " +
                                                      std::to_string(options.max_points));
  }
  return CloudError::kNone;
}

/// Finds the per-point time field (the first of kTimeFields present) and checks it like
/// find_fields does the others; every problem is kBadTimeField. `spec.found` stays false when
/// the message has none.
CloudError find_time_field(const sensor_msgs::msg::PointCloud2& msg, FieldSpec& spec,
                           CloudConversion& out) {
  const std::uint64_t point_step = msg.point_step();
  for (const char* name : kTimeFields) {
    for (const auto& field : msg.fields()) {
      if (field.name() != name) continue;
      const std::string who = std::string("time field '") + name + "'";
      if (spec.found) return out.reject(CloudError::kBadTimeField, who + " appears more than once");
      spec.name = name;
      spec.found = true;
      spec.offset = field.offset();
      spec.datatype = field.datatype();
      const std::size_t size = datatype_size(field.datatype());
      if (size == 0)
        return out.reject(CloudError::kBadTimeField, who + " has datatype " +
                                                         std::to_string(field.datatype()) +
                                                         " (not a PointField datatype 1..8)");
      if (field.count() != 1)
        return out.reject(CloudError::kBadTimeField,
                          who + " has count " + std::to_string(field.count()) + " (expected 1)");
      if (static_cast<std::uint64_t>(field.offset()) + size > point_step)
        return out.reject(CloudError::kBadTimeField,
                          who + " (offset " + std::to_string(field.offset()) + ", " +
                              std::to_string(size) + " bytes) does not fit in point_step " +
                              std::to_string(point_step));
    }
    if (spec.found) return CloudError::kNone;
  }
  return CloudError::kNone;
}

/// The raw time values of the kept points (`raw`, in the field's unit) as seconds relative to
/// the header stamp in out.cloud.times: integer fields are nanoseconds, float fields seconds;
/// relative when every time is within kMaxPointTime of 0, else (FLOAT64 only) absolute seconds
/// or nanoseconds within kMaxPointTime of the stamp.
CloudError convert_times(const sensor_msgs::msg::PointCloud2& msg, const FieldSpec& spec,
                         const std::vector<double>& raw, CloudConversion& out) {
  const bool is_float = spec.datatype == kFloat32 || spec.datatype == kFloat64;
  const double unit = is_float ? 1.0 : 1e-9;
  const std::string who = std::string("time field '") + spec.name + "'";
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (!std::isfinite(raw[i]))
      return out.reject(CloudError::kBadTimeField,
                        who + ": point " + std::to_string(i) + " has a non-finite time");
    lo = i == 0 ? raw[i] : std::min(lo, raw[i]);
    hi = i == 0 ? raw[i] : std::max(hi, raw[i]);
  }
  auto& times = out.cloud.times;
  times.resize(raw.size());
  if (std::max(std::abs(lo), std::abs(hi)) * unit <= kMaxPointTime) {
    for (std::size_t i = 0; i < raw.size(); ++i) times[i] = static_cast<float>(raw[i] * unit);
    return CloudError::kNone;
  }
  // Absolute: seconds (or nanoseconds) since the epoch, relative to the stamp as
  // (value - sec) - nanosec, which keeps the double's resolution (~0.2 us today).
  const double sec = msg.header().stamp().sec();
  const double nanosec = msg.header().stamp().nanosec();
  if (spec.datatype == kFloat64) {
    for (const double scale : {1.0, 1e-9}) {
      auto relative = [&](double v) {
        return scale == 1.0 ? (v - sec) - nanosec * 1e-9 : (v - sec * 1e9 - nanosec) * 1e-9;
      };
      if (std::abs(relative(lo)) <= kMaxPointTime && std::abs(relative(hi)) <= kMaxPointTime) {
        for (std::size_t i = 0; i < raw.size(); ++i)
          times[i] = static_cast<float>(relative(raw[i]));
        out.absolute_time = true;
        return CloudError::kNone;
      }
    }
  }
  times.clear();
  return out.reject(CloudError::kBadTimeField,
                    who + ": times from " + std::to_string(lo) + " to " + std::to_string(hi) + " " +
                        (is_float ? "s" : "ns") + " are neither relative (within 1 s of 0) nor" +
                        (spec.datatype == kFloat64 ? " absolute within 1 s of the stamp "
                                                   : " (FLOAT64 only) absolute; stamp ") +
                        std::to_string(msg.header().stamp().sec()) + "." +
                        std::to_string(msg.header().stamp().nanosec()) + " s");
}

/// The common case (native float32 x, y, z; intensity not wanted): written in place, with no
/// per-point capacity checks or datatype switches.
void read_float_xyz(const sensor_msgs::msg::PointCloud2& msg, PointBytes bytes,
                    const std::array<FieldSpec, 4>& specs, CloudConversion& out) {
  const std::uint64_t width = msg.width(), height = msg.height();
  const std::uint64_t point_step = msg.point_step(), row_step = msg.row_step();
  auto& points = out.cloud.points;
  points.resize(static_cast<std::size_t>(width * height));
  Eigen::Vector3f* next = points.data();
  const std::size_t ox = specs[0].offset, oy = specs[1].offset, oz = specs[2].offset;
  const std::uint8_t* data = bytes.data;
  for (std::uint64_t row = 0; row < height; ++row) {
    const std::uint8_t* p = data + row * row_step;
    for (std::uint64_t col = 0; col < width; ++col, p += point_step) {
      float x, y, z;
      std::memcpy(&x, p + ox, 4);
      std::memcpy(&y, p + oy, 4);
      std::memcpy(&z, p + oz, 4);
      // x - x is 0 for finite x and NaN for NaN or +-Inf: one test for all three.
      if ((x - x) + (y - y) + (z - z) == 0.0f) {
        *next++ = Eigen::Vector3f(x, y, z);
      } else {
        ++out.non_finite;
      }
    }
  }
  points.resize(static_cast<std::size_t>(next - points.data()));
}

/// Any layout: float32 or float64 coordinates in either byte order, and the intensity if
/// `with_intensity` (any numeric type; a non-finite one rejects the message), and the raw
/// time values into `raw_times` if `time`.
CloudError read_any_layout(const sensor_msgs::msg::PointCloud2& msg, PointBytes bytes,
                           const std::array<FieldSpec, 4>& specs, bool with_intensity,
                           const FieldSpec* time, std::vector<double>& raw_times,
                           CloudConversion& out) {
  const std::uint64_t width = msg.width(), height = msg.height();
  const std::uint64_t point_step = msg.point_step(), row_step = msg.row_step();
  const bool swap = msg.is_bigendian() != host_is_big_endian();
  const bool native_float = !swap && specs[0].datatype == kFloat32 &&
                            specs[1].datatype == kFloat32 && specs[2].datatype == kFloat32;
  auto& points = out.cloud.points;
  auto& intensities = out.cloud.intensities;
  points.reserve(static_cast<std::size_t>(width * height));
  if (with_intensity) intensities.reserve(static_cast<std::size_t>(width * height));
  if (time) raw_times.reserve(static_cast<std::size_t>(width * height));
  const std::uint8_t* data = bytes.data;
  for (std::uint64_t row = 0; row < height; ++row) {
    const std::uint8_t* row_ptr = data + row * row_step;
    for (std::uint64_t col = 0; col < width; ++col) {
      const std::uint8_t* p = row_ptr + col * point_step;
      Eigen::Vector3f v;
      if (native_float) {
        std::memcpy(&v.x(), p + specs[0].offset, 4);
        std::memcpy(&v.y(), p + specs[1].offset, 4);
        std::memcpy(&v.z(), p + specs[2].offset, 4);
      } else {
        v.x() = read_as_float(p + specs[0].offset, specs[0].datatype, swap);
        v.y() = read_as_float(p + specs[1].offset, specs[1].datatype, swap);
        v.z() = read_as_float(p + specs[2].offset, specs[2].datatype, swap);
      }
      if (!std::isfinite(v.x()) || !std::isfinite(v.y()) || !std::isfinite(v.z())) {
        ++out.non_finite;
        continue;
      }
      points.push_back(v);
      if (with_intensity) {
        const float i = read_as_float(p + specs[3].offset, specs[3].datatype, swap);
        if (!std::isfinite(i))
          return out.reject(
              CloudError::kNonFiniteIntensity,
              "point " + std::to_string(row * width + col) + " has intensity " + std::to_string(i));
        intensities.push_back(i);
      }
      if (time) raw_times.push_back(read_as_double(p + time->offset, time->datatype, swap));
    }
  }
  return CloudError::kNone;
}

}  // namespace

CloudError from_pointcloud2(const sensor_msgs::msg::PointCloud2& msg,
                            const CloudConversionOptions& options, CloudConversion& out) {
  return from_pointcloud2(msg, msg.data().data(), msg.data().size(), options, out);
}

CloudError from_pointcloud2(const sensor_msgs::msg::PointCloud2& msg, const std::uint8_t* data,
                            std::size_t data_size, const CloudConversionOptions& options,
                            CloudConversion& out) {
  const PointBytes bytes{data, data_size};
  out.error = CloudError::kNone;
  out.message.clear();
  out.cloud.points.clear();
  out.cloud.intensities.clear();
  out.cloud.times.clear();
  out.time_field.clear();
  out.absolute_time = false;
  out.non_finite = 0;
  out.total_points = static_cast<std::size_t>(static_cast<std::uint64_t>(msg.width()) *
                                              static_cast<std::uint64_t>(msg.height()));
  if (msg.header().stamp().nanosec() >= 1'000'000'000u)
    return out.reject(
        CloudError::kBadStamp,
        "header stamp nanosec " + std::to_string(msg.header().stamp().nanosec()) + " >= 1e9");
  std::array<FieldSpec, 4> specs{{{"x"}, {"y"}, {"z"}, {"intensity"}}};
  if (find_fields(msg, specs, out) != CloudError::kNone) return out.error;
  FieldSpec time{""};
  if (options.read_time && find_time_field(msg, time, out) != CloudError::kNone) return out.error;
  if (time.found) out.time_field = time.name;
  if (check_extent(msg, bytes, options, out) != CloudError::kNone) return out.error;
  if (out.total_points == 0) return CloudError::kNone;
  const bool with_intensity = options.read_intensity && specs[3].found;
  const bool native_float = msg.is_bigendian() == host_is_big_endian() &&
                            specs[0].datatype == kFloat32 && specs[1].datatype == kFloat32 &&
                            specs[2].datatype == kFloat32;
  if (native_float && !with_intensity && !time.found) {
    read_float_xyz(msg, bytes, specs, out);
    return CloudError::kNone;
  }
  std::vector<double> raw_times;
  if (read_any_layout(msg, bytes, specs, with_intensity, time.found ? &time : nullptr, raw_times,
                      out) != CloudError::kNone)
    return out.error;
  if (time.found) return convert_times(msg, time, raw_times, out);
  return CloudError::kNone;
}

const char* to_string(TimeLayout layout) {
  switch (layout) {
    case TimeLayout::kVelodyne:
      return "velodyne";
    case TimeLayout::kOuster:
      return "ouster";
    case TimeLayout::kHesai:
      return "hesai";
    case TimeLayout::kLivox:
      return "livox";
  }
  return "unknown";
}

std::optional<TimeLayout> time_layout_from_string(const std::string& name) {
  for (const TimeLayout layout :
       {TimeLayout::kVelodyne, TimeLayout::kOuster, TimeLayout::kHesai, TimeLayout::kLivox}) {
    if (name == to_string(layout)) return layout;
  }
  return std::nullopt;
}

sensor_msgs::msg::PointCloud2 to_pointcloud2(const PointCloud& cloud, Stamp stamp,
                                             const std::string& frame_id, TimeLayout layout) {
  if (const auto why = point_times_error(cloud))
    throw std::invalid_argument("to_pointcloud2: " + *why);
  const std::size_t n = cloud.points.size();
  const bool with_time = cloud.has_times();
  const bool unsigned_ns = layout == TimeLayout::kOuster || layout == TimeLayout::kLivox;
  if (with_time && unsigned_ns) {
    for (const float t : cloud.times) {
      if (t < 0.0f)
        throw std::invalid_argument(std::string("to_pointcloud2: the ") + to_string(layout) +
                                    " layout holds no negative time (" + std::to_string(t) + " s)");
    }
  }
  sensor_msgs::msg::PointCloud2 msg;
  msg.header().stamp(to_time(stamp));
  msg.header().frame_id(frame_id);
  const char* names[4] = {"x", "y", "z", "intensity"};
  std::vector<sensor_msgs::msg::PointField> fields(4);
  for (std::uint32_t k = 0; k < 4; ++k) {
    fields[k].name(names[k]);
    fields[k].offset(4 * k);
    fields[k].datatype(kFloat32);
    fields[k].count(1);
  }
  std::uint32_t step = 16;
  if (with_time) {
    sensor_msgs::msg::PointField time;
    const char* time_names[] = {"time", "t", "timestamp", "offset_time"};
    const std::uint8_t types[] = {kFloat32, kUint32, kFloat64, kUint32};
    const auto k = static_cast<std::size_t>(layout);
    time.name(time_names[k]);
    time.offset(16);
    time.datatype(types[k]);
    time.count(1);
    fields.push_back(time);
    step = layout == TimeLayout::kHesai ? 24 : 20;
  }
  msg.fields(std::move(fields));
  const bool with_intensity = cloud.intensities.size() == n;
  msg.height(1);
  msg.width(static_cast<std::uint32_t>(n));
  msg.is_bigendian(host_is_big_endian());
  msg.point_step(step);
  msg.row_step(static_cast<std::uint32_t>(step * n));
  msg.is_dense(true);
  std::vector<std::uint8_t> data(step * n);
  std::uint8_t* p = data.data();
  const double stamp_s = stamp.seconds();
  for (std::size_t i = 0; i < n; ++i, p += step) {
    const Eigen::Vector3f& v = cloud.points[i];
    const float record[4] = {v.x(), v.y(), v.z(), with_intensity ? cloud.intensities[i] : 0.0f};
    std::memcpy(p, record, 16);
    if (!with_time) continue;
    const float t = cloud.times[i];
    if (layout == TimeLayout::kVelodyne) {
      std::memcpy(p + 16, &t, 4);
    } else if (layout == TimeLayout::kHesai) {
      const double absolute = stamp_s + static_cast<double>(t);
      std::memcpy(p + 16, &absolute, 8);
    } else {
      const auto ns = static_cast<std::uint32_t>(std::llround(static_cast<double>(t) * 1e9));
      std::memcpy(p + 16, &ns, 4);
    }
  }
  msg.data(std::move(data));
  return msg;
}

}  // namespace litamin2::dds
