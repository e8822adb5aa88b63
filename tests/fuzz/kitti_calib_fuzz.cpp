// Fuzz harness: io::read_kitti_velo_to_cam (calib.txt, raw-data and per-sequence tables). The
// first byte gives the sequence (255: none); the rest is the file. Properties: only IoError
// and std::invalid_argument are thrown; an accepted calibration is a rigid transform (a
// rotation, not a reflection, and a bounded translation).

#include "fuzz_support.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_calib.hpp"

#include <stdexcept>

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::optional<int> sequence =
      data[0] == 255 ? std::nullopt : std::optional<int>(data[0] % 32);
  try {
    fuzz::check_pose(io::read_kitti_velo_to_cam(fuzz::as_file(data + 1, size - 1), sequence));
    fuzz::accepted() = true;
  } catch (const io::IoError&) {
  }
  return 0;
}
