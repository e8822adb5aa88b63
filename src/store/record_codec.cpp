#include "litamin2/store/record_codec.hpp"

#include "litamin2/core/value_checks.hpp"
#include "litamin2/core/voxel_key.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace litamin2::store {

namespace {

// Byte-wise little-endian writes and reads: portable, and compilers turn them into plain
// loads and stores on little-endian hosts.
void put_u32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void put_u64(unsigned char* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
std::uint32_t get_u32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}
std::uint64_t get_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}

void put_f32(unsigned char* p, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  put_u32(p, bits);
}
float get_f32(const unsigned char* p) {
  const std::uint32_t bits = get_u32(p);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}
void put_f64(unsigned char* p, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, 8);
  put_u64(p, bits);
}
double get_f64(const unsigned char* p) {
  const std::uint64_t bits = get_u64(p);
  double d;
  std::memcpy(&d, &bits, 8);
  return d;
}

void check_size(const char* what, std::size_t size, std::size_t expected) {
  if (size != expected) {
    throw std::invalid_argument(std::string(what) + " blob has " + std::to_string(size) +
                                " bytes, expected " + std::to_string(expected));
  }
}

unsigned char* bytes(std::string& s) {
  return reinterpret_cast<unsigned char*>(s.data());
}

void check_pose(const char* what, const Eigen::Matrix<double, 3, 4>& m) {
  if (const auto why = checks::rotation_error(m.leftCols<3>()))
    throw std::invalid_argument(std::string(what) + ": rotation " + *why);
  if (const auto why = checks::position_error(m.col(3)))
    throw std::invalid_argument(std::string(what) + ": translation " + *why);
}

void check_matrix6(const char* what, const Matrix6d& m) {
  if (const auto why = checks::covariance_error<6>(m))
    throw std::invalid_argument(std::string(what) + " " + *why);
}

/// The distribution checks of the codec, on the values as stored (float mean, covariance triangle
/// and count).
void check_distribution(std::size_t index, const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov,
                        std::int64_t count) {
  if (count < 0)  // (the message the store's callers have always seen)
    throw std::invalid_argument("a distribution has a negative point count " +
                                std::to_string(count) + " (distribution " + std::to_string(index) +
                                ")");
  const std::string what = "distribution " + std::to_string(index) + ": ";
  if (const auto why = checks::position_error(mean))
    throw std::invalid_argument(what + "mean " + *why);
  if (const auto why = checks::covariance_error<3>(cov))
    throw std::invalid_argument(what + "covariance " + *why);
  if (count < 1 || count > std::numeric_limits<int>::max())
    throw std::invalid_argument(what + "point count " + std::to_string(count) +
                                " is not in 1 .. 2^31 - 1");
}

/// check_distribution's verdict without its cost in the common case: the bounds (count, finite
/// and bounded mean and covariance, symmetry) as value_checks.hpp tests them, and positive
/// semi-definiteness on the closed-form eigenvalues (`eigen`: computeDirect of `cov`, which the
/// decoder's regularisation uses too) with half the tolerance. Only a distribution that fails
/// here (invalid, or within rounding of the boundary) goes through check_distribution, which
/// gives the verdict and its message as before: the checks are the same, their cost is one
/// closed-form decomposition and no message built per distribution.
bool plainly_bounded(const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov, std::int64_t count) {
  if (count < 1 || count > std::numeric_limits<int>::max()) return false;
  if (!mean.allFinite() || !(mean.cwiseAbs().maxCoeff() <= checks::kMaxPosition)) return false;
  if (!cov.allFinite()) return false;
  const double scale = cov.cwiseAbs().maxCoeff();
  if (!(scale <= checks::kMaxCovarianceEntry)) return false;
  return (cov - cov.transpose()).cwiseAbs().maxCoeff() <= checks::kMatrixTolerance * scale;
}

bool plainly_semi_definite(const Eigen::Vector3d& eigenvalues) {
  const double largest = eigenvalues.cwiseAbs().maxCoeff();
  return eigenvalues.minCoeff() >= -0.5 * checks::kMatrixTolerance * largest;
}

/// check_distribution, through the plain checks first.
void check_distribution_fast(std::size_t index, const Eigen::Vector3d& mean,
                             const Eigen::Matrix3d& cov, std::int64_t count) {
  if (plainly_bounded(mean, cov, count)) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(cov, Eigen::EigenvaluesOnly);
    if (plainly_semi_definite(eig.eigenvalues())) return;
  }
  check_distribution(index, mean, cov, count);
}

/// The covariance of the stored upper triangle (xx, xy, xz, yy, yz, zz).
Eigen::Matrix3d from_triangle(const float* t) {
  Eigen::Matrix3d c;
  c << t[0], t[1], t[2],  //
      t[1], t[3], t[4],   //
      t[2], t[4], t[5];
  return c;
}

}  // namespace

std::string encode_pose(const Eigen::Isometry3d& pose) {
  std::string out(kPoseBytes, '\0');
  const Eigen::Matrix<double, 3, 4> m = pose.matrix().topRows<3>();
  check_pose("pose", m);
  for (int i = 0; i < 12; ++i) put_f64(bytes(out) + 8 * i, m.data()[i]);
  return out;
}

Eigen::Isometry3d decode_pose(const void* data, std::size_t size) {
  check_size("pose", size, kPoseBytes);
  const auto* p = static_cast<const unsigned char*>(data);
  Eigen::Matrix<double, 3, 4> m;
  for (int i = 0; i < 12; ++i) m.data()[i] = get_f64(p + 8 * i);
  check_pose("pose blob", m);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.matrix().topRows<3>() = m;
  return pose;
}

std::string encode_matrix6(const Matrix6d& m) {
  check_matrix6("6x6 matrix", m);
  std::string out(kMatrix6Bytes, '\0');
  for (int i = 0; i < 36; ++i) put_f64(bytes(out) + 8 * i, m.data()[i]);
  return out;
}

Matrix6d decode_matrix6(const void* data, std::size_t size) {
  check_size("6x6 matrix", size, kMatrix6Bytes);
  const auto* p = static_cast<const unsigned char*>(data);
  Matrix6d m;
  for (int i = 0; i < 36; ++i) m.data()[i] = get_f64(p + 8 * i);
  check_matrix6("6x6 matrix blob", m);
  return m;
}

std::string encode_distributions(const std::vector<Distribution>& distributions) {
  std::string out(distributions.size() * kDistributionBytes, '\0');
  unsigned char* p = bytes(out);
  for (std::size_t k = 0; k < distributions.size(); ++k) {
    const Distribution& d = distributions[k];
    const Eigen::Matrix3d& c = d.cov;
    const double values[9] = {d.mean.x(), d.mean.y(), d.mean.z(), c(0, 0), c(0, 1),
                              c(0, 2),    c(1, 1),    c(1, 2),    c(2, 2)};
    // Checked as given (bounded, so that the conversion to float is defined) and as they will be
    // read back, in float.
    check_distribution_fast(k, d.mean, c, d.count);
    float stored[9];
    for (int i = 0; i < 9; ++i) stored[i] = static_cast<float>(values[i]);
    check_distribution_fast(k, Eigen::Vector3f(stored[0], stored[1], stored[2]).cast<double>(),
                            from_triangle(stored + 3), d.count);
    for (int i = 0; i < 9; ++i) put_f32(p + 4 * i, values[i]);
    put_u32(p + 36, static_cast<std::uint32_t>(d.count));
    p += kDistributionBytes;
  }
  return out;
}

std::vector<Distribution> decode_distributions(const void* data, std::size_t size,
                                               const RegularizerConfig& regularizer) {
  if (size % kDistributionBytes != 0) {
    throw std::invalid_argument("distributions blob has " + std::to_string(size) +
                                " bytes, not a multiple of " + std::to_string(kDistributionBytes));
  }
  const auto* p = static_cast<const unsigned char*>(data);
  std::vector<Distribution> out(size / kDistributionBytes);
  for (std::size_t k = 0; k < out.size(); ++k) {
    Distribution& d = out[k];
    float v[9];
    for (int i = 0; i < 9; ++i) v[i] = get_f32(p + 4 * i);
    const std::uint32_t count = get_u32(p + 36);
    d.mean = Eigen::Vector3d(v[0], v[1], v[2]);
    const Eigen::Matrix3d raw = from_triangle(v + 3);
    // One closed-form decomposition for the check and the regularisation.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    const bool bounded = plainly_bounded(d.mean, raw, count);
    if (bounded) eig.computeDirect(raw);
    if (!bounded || !plainly_semi_definite(eig.eigenvalues())) {
      check_distribution(k, d.mean, raw, count);  // throws why, or accepts a borderline one
      if (!bounded) eig.computeDirect(raw);
    }
    regularize_for_terms(regularizer, eig, d.cov, d.shape_cov, d.shape_cov_inv);
    d.count = static_cast<int>(count);
    p += kDistributionBytes;
  }
  return out;
}

std::string encode_descriptor(const mapping::PlaceDescriptor& d) {
  const std::size_t cells = static_cast<std::size_t>(d.rings) * static_cast<std::size_t>(d.sectors);
  if (d.rings < 0 || d.sectors < 0 || d.rings > 65535 || d.sectors > 65535 ||
      d.ring_key.size() != static_cast<std::size_t>(d.rings) || d.cells.size() != cells)
    throw std::invalid_argument("inconsistent place descriptor");
  std::string out(4 + 4 * d.ring_key.size() + cells, '\0');
  unsigned char* p = bytes(out);
  p[0] = static_cast<unsigned char>(d.rings & 0xff);
  p[1] = static_cast<unsigned char>(d.rings >> 8);
  p[2] = static_cast<unsigned char>(d.sectors & 0xff);
  p[3] = static_cast<unsigned char>(d.sectors >> 8);
  p += 4;
  for (float v : d.ring_key) {
    put_f32(p, v);
    p += 4;
  }
  std::memcpy(p, d.cells.data(), cells);
  return out;
}

mapping::PlaceDescriptor decode_descriptor(const void* data, std::size_t size, bool with_cells) {
  const auto* p = static_cast<const unsigned char*>(data);
  if (size < 4) throw std::invalid_argument("descriptor blob too short");
  mapping::PlaceDescriptor d;
  d.rings = p[0] | (p[1] << 8);
  d.sectors = p[2] | (p[3] << 8);
  const std::size_t cells = static_cast<std::size_t>(d.rings) * static_cast<std::size_t>(d.sectors);
  check_size("descriptor", size, 4 + 4 * static_cast<std::size_t>(d.rings) + cells);
  p += 4;
  d.ring_key.resize(static_cast<std::size_t>(d.rings));
  for (float& v : d.ring_key) {
    v = get_f32(p);
    if (!std::isfinite(v)) throw std::invalid_argument("non-finite descriptor ring key");
    p += 4;
  }
  if (with_cells) d.cells.assign(p, p + cells);
  return d;
}

std::string encode_tile_voxels(const std::vector<mapping::MapTile::Voxel>& voxels) {
  std::string out(voxels.size() * kTileVoxelBytes, '\0');
  unsigned char* p = bytes(out);
  for (const mapping::MapTile::Voxel& v : voxels) {
    const VoxelMoments& m = v.moments;
    if (m.count <= 0 || !m.sum.allFinite() || !m.sum_sq.allFinite())
      throw std::invalid_argument("a tile voxel has no points or a non-finite sum");
    put_u64(p, v.key);
    put_u32(p + 8, static_cast<std::uint32_t>(m.count));
    for (int i = 0; i < 3; ++i) put_f64(p + 12 + 8 * i, m.sum(i));
    for (int i = 0; i < 6; ++i) put_f64(p + 36 + 8 * i, m.sum_sq(i));
    p += kTileVoxelBytes;
  }
  return out;
}

std::vector<mapping::MapTile::Voxel> decode_tile_voxels(const void* data, std::size_t size,
                                                        double voxel_size) {
  if (size % kTileVoxelBytes != 0) {
    throw std::invalid_argument("tile voxels blob has " + std::to_string(size) +
                                " bytes, not a multiple of " + std::to_string(kTileVoxelBytes));
  }
  const auto* p = static_cast<const unsigned char*>(data);
  std::vector<mapping::MapTile::Voxel> out(size / kTileVoxelBytes);
  for (mapping::MapTile::Voxel& v : out) {
    v.key = get_u64(p);
    const std::uint32_t count = get_u32(p + 8);
    if (count == 0 || count > static_cast<std::uint32_t>(std::numeric_limits<int>::max()))
      throw std::invalid_argument("a tile voxel has a point count " + std::to_string(count) +
                                  " out of range");
    VoxelMoments& m = v.moments;
    m.count = static_cast<int>(count);
    for (int i = 0; i < 3; ++i) m.sum(i) = get_f64(p + 12 + 8 * i);
    for (int i = 0; i < 6; ++i) m.sum_sq(i) = get_f64(p + 36 + 8 * i);
    if (!m.sum.allFinite() || !m.sum_sq.allFinite())
      throw std::invalid_argument("a tile voxel holds a non-finite sum");
    m.origin = (unpack_voxel(v.key).cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_size;
    p += kTileVoxelBytes;
  }
  return out;
}

std::string encode_tile_summary(const mapping::TileSummary& s) {
  std::string out(4 * (6 + 3 * s.sample.size()), '\0');
  unsigned char* p = bytes(out);
  auto put3 = [&](const Eigen::Vector3f& v) {
    for (int i = 0; i < 3; ++i, p += 4) put_f32(p, v(i));
  };
  put3(s.min_bound);
  put3(s.max_bound);
  for (const Eigen::Vector3f& m : s.sample) put3(m);
  return out;
}

void decode_tile_summary(const void* data, std::size_t size, mapping::TileSummary& s) {
  if (size < 24 || size % 12 != 0)
    throw std::invalid_argument("tile summary blob has " + std::to_string(size) + " bytes");
  const auto* p = static_cast<const unsigned char*>(data);
  auto get3 = [&] {
    Eigen::Vector3f v(get_f32(p), get_f32(p + 4), get_f32(p + 8));
    p += 12;
    if (!v.allFinite()) throw std::invalid_argument("tile summary holds a non-finite value");
    return v;
  };
  s.min_bound = get3();
  s.max_bound = get3();
  s.sample.clear();
  for (std::size_t i = 24; i < size; i += 12) s.sample.push_back(get3());
}

}  // namespace litamin2::store
