// Fuzz harness: a litamin2_zero_copy/PlainScan as litamin2d's zero-copy input receives it
// (streams[].zero_copy_topic). With data-sharing, the reader sees the writer's shared memory laid
// over the struct: the input's bytes are that memory (a prefix of the 2,097,232-byte sample;
// the rest is zero), converted by dds::from_plain_scan. Without data-sharing (the writer not on
// this host), the same bytes arrive as CDR through the reader's type; that path is run too.
// Properties: nothing throws; an accepted scan has at most point_count finite points, within
// the limit, times only when asked for, one per point, each within +-1 s.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "cdr_payload.hpp"
#include "fuzz_support.hpp"
#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/plain_scan_conversion.hpp"
#include "litamin2_zero_copy/msg/PlainScanPubSubTypes.h"

using namespace litamin2;

namespace {

void check_conversion(const litamin2_zero_copy::msg::PlainScan& scan, bool read_time) {
  dds::CloudConversionOptions options;
  options.read_time = read_time;
  options.max_points = 100'000;
  static dds::CloudConversion out;
  const dds::CloudError error = dds::from_plain_scan(scan, options, out);
  if (error != dds::CloudError::kNone) {
    LITAMIN2_FUZZ_CHECK(!out.message.empty(), "rejected with a reason");
    LITAMIN2_FUZZ_CHECK(out.cloud.points.empty(), "rejected scan has no points");
    return;
  }
  // "Accepted" (the corpus' valid-* / reject-* names) is as a deskewing daemon reads the scan.
  if (read_time) fuzz::accepted() = true;
  LITAMIN2_FUZZ_CHECK(out.cloud.points.size() + out.non_finite == scan.point_count(),
                      "every point kept or counted");
  LITAMIN2_FUZZ_CHECK(out.cloud.points.size() <= options.max_points, "within the limit");
  LITAMIN2_FUZZ_CHECK(out.cloud.intensities.empty(), "no intensities");
  for (const auto& p : out.cloud.points) LITAMIN2_FUZZ_CHECK(p.allFinite(), "finite point");
  if (!read_time || scan.has_times() == 0) {
    LITAMIN2_FUZZ_CHECK(out.cloud.times.empty(), "times only when asked for and present");
    return;
  }
  LITAMIN2_FUZZ_CHECK(out.cloud.times.size() == out.cloud.points.size(), "a time per point");
  LITAMIN2_FUZZ_CHECK(!point_times_error(out.cloud), "valid times");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto scan = std::make_unique<litamin2_zero_copy::msg::PlainScan>();
  // The shared-memory path: the bytes laid over the sample.
  std::memset(static_cast<void*>(scan.get()), 0, sizeof(litamin2_zero_copy::msg::PlainScan));
  std::memcpy(static_cast<void*>(scan.get()), data,
              std::min(size, sizeof(litamin2_zero_copy::msg::PlainScan)));
  check_conversion(*scan, true);
  check_conversion(*scan, false);
  // The network path: the bytes as CDR through the reader's checked type.
  static dds::CheckedType<litamin2_zero_copy::msg::PlainScanPubSubType> type;
  if (fuzz::deserialize(type, data, size, *scan)) check_conversion(*scan, true);
  return 0;
}
