// Fuzz harness: a litamin2/msg/MapPatch as litamin2-aggregator receives it, from raw CDR bytes
// through the reader's dds::CheckedType to dds::from_map_patch, and on into the store's codec.
// Properties: nothing throws; a rejected patch gives no keyframe and a reason; an accepted one
// is a valid keyframe (rotation, bounded translation, PSD covariances, counts >= 1) that the
// store's codec encodes without complaint and decodes back to the same values (what the network
// accepts can never poison the store), and that the daemon's conversion sends again unchanged.

#include "cdr_payload.hpp"
#include "fuzz_support.hpp"
#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "litamin2/store/record_codec.hpp"

#include <stdexcept>

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dds::CheckedType<litamin2::msg::MapPatchPubSubType> type(1 << 20);
  litamin2::msg::MapPatch msg;
  if (!fuzz::deserialize(type, data, size, msg)) return 0;
  dds::PatchConversionOptions options;
  options.max_distributions = 4096;
  const dds::PatchConversion patch = dds::from_map_patch(msg, options);
  if (!patch.ok()) {
    LITAMIN2_FUZZ_CHECK(patch.keyframe.distributions.empty() && !patch.message.empty(),
                        "rejected: no keyframe, reason");
    return 0;
  }
  const Keyframe& kf = patch.keyframe;
  fuzz::check_keyframe(kf);
  fuzz::accepted() = true;
  try {
    const std::string pose = store::encode_pose(kf.odom_pose);
    LITAMIN2_FUZZ_CHECK(
        store::decode_pose(pose.data(), pose.size()).matrix() == kf.odom_pose.matrix(),
        "store pose round trip");
    const std::string cov = store::encode_matrix6(kf.covariance);
    LITAMIN2_FUZZ_CHECK(store::decode_matrix6(cov.data(), cov.size()) == kf.covariance,
                        "store covariance round trip");
    const std::string d = store::encode_distributions(kf.distributions);
    const auto back = store::decode_distributions(d.data(), d.size(), {});
    LITAMIN2_FUZZ_CHECK(back.size() == kf.distributions.size(), "store distributions count");
    for (std::size_t i = 0; i < back.size(); ++i)
      LITAMIN2_FUZZ_CHECK(
          back[i].mean == kf.distributions[i].mean && back[i].count == kf.distributions[i].count,
          "store distribution round trip");
  } catch (const std::invalid_argument& e) {
    LITAMIN2_FUZZ_CHECK(false, std::string("the store refused an accepted patch: ") + e.what());
  }
  const dds::PatchConversion again = dds::from_map_patch(dds::to_map_patch(kf, "odom"), options);
  LITAMIN2_FUZZ_CHECK(again.ok(),
                      "the daemon's conversion of an accepted keyframe: " + again.message);
  return 0;
}
