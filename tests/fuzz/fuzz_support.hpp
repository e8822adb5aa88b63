#pragma once
// Shared by the fuzz harnesses of tests/fuzz (docs/security.md, "Fuzzing"): a check that aborts
// with a message (libFuzzer reports it as a crash, the corpus replay as a failed test), the
// file an input is handed to a file reader through, and the properties of what a parser may
// return: everything finite, bounded and valid by the checks of core/value_checks.hpp.

#include "litamin2/core/keyframe.hpp"
#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/value_checks.hpp"

#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <sys/mman.h>
#include <unistd.h>

namespace litamin2::fuzz {

/// A property of the parser's output that does not hold: abort, naming it.
#define LITAMIN2_FUZZ_CHECK(condition, what)                                                  \
  do {                                                                                        \
    if (!(condition)) {                                                                       \
      std::fprintf(stderr, "fuzz property violated: %s (%s:%d)\n", std::string(what).c_str(), \
                   __FILE__, __LINE__);                                                       \
      std::abort();                                                                           \
    }                                                                                         \
  } while (0)

/// Whether the parser accepted the last input (set by the harness). The corpus replay requires
/// every regression-* input (a finding of issue 14) to be rejected.
inline bool& accepted() {
  static bool value = false;
  return value;
}

/// The input's bytes as a file for the readers that take a path: a memfd, rewritten per input
/// (no disk, no cleanup), reached as /proc/self/fd/N.
inline std::string as_file(const std::uint8_t* data, std::size_t size) {
  static const int fd = memfd_create("litamin2-fuzz", 0);
  LITAMIN2_FUZZ_CHECK(fd >= 0, "memfd_create");
  LITAMIN2_FUZZ_CHECK(ftruncate(fd, 0) == 0, "ftruncate");
  std::size_t written = 0;
  while (written < size) {
    const ssize_t n = pwrite(fd, data + written, size - written, static_cast<off_t>(written));
    LITAMIN2_FUZZ_CHECK(n > 0, "pwrite");
    written += static_cast<std::size_t>(n);
  }
  return "/proc/self/fd/" + std::to_string(fd);
}

/// A cloud a reader returned: finite points, and either no intensities or one finite intensity
/// per point.
inline void check_cloud(const PointCloud& cloud) {
  for (const Eigen::Vector3f& p : cloud.points) LITAMIN2_FUZZ_CHECK(p.allFinite(), "point finite");
  LITAMIN2_FUZZ_CHECK(cloud.intensities.empty() || cloud.intensities.size() == cloud.points.size(),
                      "one intensity per point");
  for (float i : cloud.intensities) LITAMIN2_FUZZ_CHECK(std::isfinite(i), "intensity finite");
}

/// A rigid transform a reader returned: a rotation within tolerance, a bounded translation.
inline void check_pose(const Eigen::Isometry3d& pose) {
  const auto rotation = checks::rotation_error(pose.linear());
  LITAMIN2_FUZZ_CHECK(!rotation, "pose rotation " + rotation.value_or(""));
  const auto position = checks::position_error(pose.translation());
  LITAMIN2_FUZZ_CHECK(!position, "pose translation " + position.value_or(""));
  LITAMIN2_FUZZ_CHECK((pose.matrix().row(3) - Eigen::RowVector4d(0, 0, 0, 1)).isZero(0.0),
                      "bottom row 0 0 0 1");
}

/// A keyframe the network or the store gave: valid pose, covariance, voxel size and
/// distributions (counts >= 1, means bounded, covariances PSD and their inverses finite).
inline void check_keyframe(const Keyframe& kf) {
  check_pose(kf.odom_pose);
  const auto covariance = checks::covariance_error<6>(kf.covariance);
  LITAMIN2_FUZZ_CHECK(!covariance, "keyframe covariance " + covariance.value_or(""));
  LITAMIN2_FUZZ_CHECK(std::isfinite(kf.voxel_size) && kf.voxel_size > 0.0, "voxel size");
  for (const Distribution& d : kf.distributions) {
    LITAMIN2_FUZZ_CHECK(!checks::position_error(d.mean), "distribution mean");
    const auto cov = checks::covariance_error<3>(d.cov);
    LITAMIN2_FUZZ_CHECK(!cov, "distribution covariance " + cov.value_or(""));
    LITAMIN2_FUZZ_CHECK(d.shape_cov.allFinite() && d.shape_cov_inv.allFinite(),
                        "distribution shape finite");
    LITAMIN2_FUZZ_CHECK(d.count >= 1, "distribution count >= 1");
  }
}

}  // namespace litamin2::fuzz
