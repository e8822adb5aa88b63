// Fuzz harness: the keyframe store's BLOB decoders on bytes as a corrupt or tampered store
// file could hold them. The first byte picks the decoder (pose, 6x6 matrix, distributions).
// Properties: only std::invalid_argument is thrown; what is decoded is valid (rotation,
// bounded translation, symmetric PSD matrix, distributions with counts >= 1 and PSD
// covariances) and encodes again (poses and matrices to the very same bytes).

#include "fuzz_support.hpp"
#include "litamin2/store/record_codec.hpp"

#include <stdexcept>

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t which = data[0] % 3;
  const std::uint8_t* blob = data + 1;
  const std::size_t n = size - 1;
  try {
    if (which == 0) {
      const Eigen::Isometry3d pose = store::decode_pose(blob, n);
      fuzz::check_pose(pose);
      const std::string again = store::encode_pose(pose);
      LITAMIN2_FUZZ_CHECK(again == std::string(reinterpret_cast<const char*>(blob), n),
                          "pose re-encodes to the same bytes");
    } else if (which == 1) {
      const Matrix6d m = store::decode_matrix6(blob, n);
      LITAMIN2_FUZZ_CHECK(!checks::covariance_error<6>(m), "matrix valid");
      const std::string again = store::encode_matrix6(m);
      LITAMIN2_FUZZ_CHECK(again == std::string(reinterpret_cast<const char*>(blob), n),
                          "matrix re-encodes to the same bytes");
    } else {
      const auto distributions = store::decode_distributions(blob, n, {});
      Keyframe kf;
      kf.voxel_size = 1.0;
      kf.distributions = distributions;
      fuzz::check_keyframe(kf);
      std::vector<Distribution> raw = distributions;
      store::encode_distributions(raw);  // the regularised covariances are valid too
    }
    fuzz::accepted() = true;
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
