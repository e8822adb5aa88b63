// Fuzz harness: the trajectory readers. The first byte picks KITTI poses or TUM; the rest is
// the file. Properties: only IoError is thrown; every pose read is a rigid transform (rotation
// within tolerance, determinant +1, bounded translation) and every TUM time is finite.

#include "fuzz_support.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/trajectory.hpp"

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string file = fuzz::as_file(data + 1, size - 1);
  try {
    if (data[0] % 2 == 0) {
      for (const Eigen::Isometry3d& pose : io::read_kitti_poses(file)) fuzz::check_pose(pose);
    } else {
      for (const io::TimedPose& p : io::read_tum(file)) {
        LITAMIN2_FUZZ_CHECK(std::isfinite(p.time), "TUM time finite");
        fuzz::check_pose(p.pose);
      }
    }
    fuzz::accepted() = true;
  } catch (const io::IoError&) {
  }
  return 0;
}
