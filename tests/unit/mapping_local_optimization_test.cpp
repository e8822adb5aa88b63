// The local optimisation after each loop against the full one: on the drifting street drive,
// the local optimisations alone end within a stated distance of the full pass's poses, and
// the full pass over rigid segments within a stated distance of the keyframe-level one.

#include "litamin2/mapping/mapper.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;

namespace {

double largest_difference(const Mapper& a, const Mapper& b) {
  const auto pa = a.poses(), pb = b.poses();
  double worst = 0.0;
  for (std::size_t i = 0; i < pa.size() && i < pb.size(); ++i)
    worst = std::max(worst, (pa[i].pose.translation() - pb[i].pose.translation()).norm());
  return worst;
}

}  // namespace

TEST(MappingLocalOptimization, EndsCloseToTheFullOptimisation) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  MapperConfig keyframe_level = config;
  keyframe_level.graph.segment_keyframes = 1;
  Mapper local(config), segments(config), full(keyframe_level);
  for (const auto& kf : keyframes) {
    for (Mapper* m : {&local, &segments, &full}) {
      m->add_keyframe(kf);
      m->optimize();
    }
  }
  segments.optimize_full();
  full.optimize_full();
  ASSERT_GT(full.loops().size(), 5u);
  ASSERT_EQ(local.loops().size(), full.loops().size());
  // Tolerance (the drive drifts by 1.0 m without loops): the local optimisations alone, and
  // the full pass over 10-keyframe segments, end within 0.15 m of the keyframe-level full
  // optimisation (measured: 0.10 and 0.09 m).
  const double local_gap = largest_difference(local, full);
  const double segment_gap = largest_difference(segments, full);
  EXPECT_LT(local_gap, 0.15);
  EXPECT_LT(segment_gap, 0.15);
  std::printf("local vs full %.3f m, segments vs full %.3f m\n", local_gap, segment_gap);
}
