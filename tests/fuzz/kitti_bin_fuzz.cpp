// Fuzz harness: io::read_kitti_bin. The first byte picks the layout (auto, XYZI, XYZ) and
// whether KISS-ICP's vertical angle correction is applied; the rest is the file. Properties:
// only IoError is thrown; an accepted cloud holds finite points and finite intensities.

#include "fuzz_support.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_bin.hpp"

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  io::KittiBinOptions options;
  const io::KittiBinLayout layouts[] = {io::KittiBinLayout::kAuto, io::KittiBinLayout::kXYZI,
                                        io::KittiBinLayout::kXYZ};
  options.layout = layouts[data[0] % 3];
  options.vertical_angle_correction_deg = (data[0] & 0x80) ? 0.205 : 0.0;
  try {
    const PointCloud cloud = io::read_kitti_bin(fuzz::as_file(data + 1, size - 1), options);
    fuzz::check_cloud(cloud);
    fuzz::accepted() = true;
  } catch (const io::IoError&) {
  }
  return 0;
}
