#include "litamin2/io/kitti_bin.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "litamin2/io/file_util.hpp"
#include "litamin2/io/io_error.hpp"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "litamin2::io reads and writes little-endian binary files and assumes a little-endian host"
#endif

namespace litamin2::io {

namespace {

/// Reads float number `index` of the byte buffer (no alignment requirement).
float float_at(std::string_view bytes, std::size_t index) {
  float value;
  std::memcpy(&value, bytes.data() + index * sizeof(float), sizeof(float));
  return value;
}

bool finite3(float x, float y, float z) {
  return std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
}

/// Records the layout tests look at: the first ones of the scan. A scan's first 16k points hold
/// several rings, plenty to tell the layouts apart; testing all of a 120k-point scan cost more
/// than reading it (a third of the offline tool's time on scans whose size fits both layouts).
constexpr std::size_t kDetectionRecords = 16384;

/// Records of `stride` floats to test: the whole file up to kDetectionRecords.
std::size_t detection_records(std::string_view bytes, std::size_t stride) {
  return std::min(kDetectionRecords, bytes.size() / (stride * sizeof(float)));
}

/// Fraction of records that are implausible under a layout with `stride` floats per record.
double bad_fraction(std::string_view bytes, std::size_t stride) {
  const std::size_t n = detection_records(bytes, stride);
  if (n == 0) return 0.0;
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t b = i * stride;
    bool ok = finite3(float_at(bytes, b), float_at(bytes, b + 1), float_at(bytes, b + 2));
    if (stride == 4) {
      const float intensity = float_at(bytes, b + 3);
      ok = ok && intensity >= 0.0f && intensity < 256.0f;  // false for NaN as well
    }
    if (!ok) ++bad;
  }
  return static_cast<double>(bad) / static_cast<double>(n);
}

/// Median distance between consecutive finite points under a layout (infinity if undefined).
/// The median is taken over the squared distances and its square root returned: the square
/// root is monotonic, so that is the median of the distances, bit for bit, with one square
/// root instead of one a record.
double median_step(std::string_view bytes, std::size_t stride) {
  const std::size_t n = detection_records(bytes, stride);
  std::vector<double> squared_steps;
  squared_steps.reserve(n);
  bool have_prev = false;
  Eigen::Vector3d prev;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t b = i * stride;
    const Eigen::Vector3d p(float_at(bytes, b), float_at(bytes, b + 1), float_at(bytes, b + 2));
    if (!p.allFinite()) continue;
    if (have_prev) squared_steps.push_back((p - prev).squaredNorm());
    prev = p;
    have_prev = true;
  }
  if (squared_steps.empty()) return std::numeric_limits<double>::infinity();
  auto mid = squared_steps.begin() + static_cast<std::ptrdiff_t>(squared_steps.size() / 2);
  std::nth_element(squared_steps.begin(), mid, squared_steps.end());
  return std::sqrt(*mid);
}

KittiBinLayout detect_layout(const std::string& path, std::string_view bytes) {
  const std::size_t size = bytes.size();
  const bool fits_xyzi = size % 16 == 0;
  const bool fits_xyz = size % 12 == 0;
  if (fits_xyzi && !fits_xyz) return KittiBinLayout::kXYZI;
  if (fits_xyz && !fits_xyzi) return KittiBinLayout::kXYZ;
  if (!fits_xyz && !fits_xyzi) {
    throw IoError(path, "size " + std::to_string(size) +
                            " bytes is a multiple of neither 16 (x,y,z,intensity float32) nor 12 "
                            "(x,y,z float32); truncated or not a KITTI .bin scan");
  }
  const double bad_xyzi = bad_fraction(bytes, 4);
  const double bad_xyz = bad_fraction(bytes, 3);
  if (bad_xyzi < bad_xyz) return KittiBinLayout::kXYZI;
  if (bad_xyz < bad_xyzi) return KittiBinLayout::kXYZ;
  return median_step(bytes, 3) < median_step(bytes, 4) ? KittiBinLayout::kXYZ
                                                       : KittiBinLayout::kXYZI;
}

}  // namespace

void apply_vertical_angle_correction(PointCloud& cloud, double angle_deg) {
  if (angle_deg == 0.0) return;
  const double angle = angle_deg * (3.14159265358979323846 / 180.0);
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    Eigen::Vector3f& point = cloud.points[i];
    const Eigen::Vector3d pt = point.cast<double>();
    // Exactly KISS-ICP's CorrectKITTIScan with a configurable angle.
    const Eigen::Vector3d rotation_vector = pt.cross(Eigen::Vector3d(0., 0., 1.));
    const double axis_norm = rotation_vector.norm();
    if (!(axis_norm > 0.0)) continue;  // on the z axis: no defined tilt direction
    const Eigen::Vector3d corrected = Eigen::AngleAxisd(angle, rotation_vector / axis_norm) * pt;
    if (!(corrected.cwiseAbs().maxCoeff() <= kFloatMax))
      throw std::range_error("point " + std::to_string(i) +
                             " leaves the float range when corrected");
    point = corrected.cast<float>();
  }
}

PointCloud read_kitti_bin(const std::string& path, const KittiBinOptions& options) {
  const FileBuffer buffer = read_file_buffer(path);
  const std::string_view bytes = buffer.view();
  if (bytes.empty()) throw IoError(path, "empty file (0 bytes), not a scan");
  KittiBinLayout layout = options.layout;
  if (layout == KittiBinLayout::kAuto) layout = detect_layout(path, bytes);
  const std::size_t stride = layout == KittiBinLayout::kXYZI ? 4 : 3;
  const std::size_t record = stride * sizeof(float);
  if (bytes.size() % record != 0) {
    throw IoError(path, "size " + std::to_string(bytes.size()) + " bytes is not a multiple of " +
                            std::to_string(record) +
                            (stride == 4 ? " (x,y,z,intensity float32)" : " (x,y,z float32)"));
  }
  const std::size_t n = bytes.size() / record;
  PointCloud cloud;
  // Sized for every record and cut to the finite ones at the end: a store a point instead of
  // push_back's capacity check (Eigen's vectors are not zeroed by resize).
  cloud.points.resize(n);
  if (stride == 4) cloud.intensities.resize(n);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t b = i * stride;
    const Eigen::Vector3f p(float_at(bytes, b), float_at(bytes, b + 1), float_at(bytes, b + 2));
    if (!p.allFinite()) continue;
    cloud.points[kept] = p;
    if (stride == 4) {
      const float intensity = float_at(bytes, b + 3);
      if (!std::isfinite(intensity))
        throw IoError(path, "point " + std::to_string(i) + ": intensity " +
                                std::to_string(intensity) + " is not finite");
      cloud.intensities[kept] = intensity;
    }
    ++kept;
  }
  cloud.points.resize(kept);
  if (stride == 4) cloud.intensities.resize(kept);
  try {
    apply_vertical_angle_correction(cloud, options.vertical_angle_correction_deg);
  } catch (const std::range_error& e) {
    throw IoError(path, std::string("vertical angle correction: ") + e.what());
  }
  return cloud;
}

void write_kitti_bin(const std::string& path, const PointCloud& cloud) {
  if (cloud.has_intensities() && cloud.intensities.size() != cloud.points.size()) {
    throw std::invalid_argument(
        "write_kitti_bin(" + path + "): " + std::to_string(cloud.intensities.size()) +
        " intensities for " + std::to_string(cloud.points.size()) + " points");
  }
  std::vector<float> data;
  data.reserve(cloud.points.size() * 4);
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    data.insert(data.end(),
                {p.x(), p.y(), p.z(), cloud.has_intensities() ? cloud.intensities[i] : 0.0f});
  }
  write_file_bytes(path, data.data(), data.size() * sizeof(float));
}

}  // namespace litamin2::io
