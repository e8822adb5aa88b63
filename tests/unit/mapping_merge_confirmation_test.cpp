// The confirmation of loops between two groups of streams (merge_confirmation.hpp): a single
// look-alike match does not merge two vehicles' frames, two agreeing loops at separate places
// do, and a loop that contradicts the pending one (a 90-degree alias) confirms nothing.

#include "litamin2/mapping/merge_confirmation.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace litamin2;
using namespace litamin2::mapping;

namespace {

Eigen::Isometry3d planar(double x, double y, double yaw_deg) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  p.translation() = Eigen::Vector3d(x, y, 0.0);
  return p;
}

/// Two vehicles on one straight street (x axis), 2 m between keyframes, each in its own
/// frame: a from x = 0 (its frame is the world's), b from x = 0 too but 1 s later, its frame
/// turned by 30 degrees and 500 m away from a's.
class MergeConfirmationTest : public ::testing::Test {
 protected:
  MergeConfirmationTest() : graph(20, 30.0) {
    b_frame = planar(500.0, -200.0, 30.0);
    for (std::uint64_t i = 0; i < 100; ++i) {
      add("a", i, planar(2.0 * i, 0.0, 0.0), 0);
      add("b", i, b_frame.inverse() * planar(2.0 * i, 0.0, 0.0), 1000000000);
    }
  }

  void add(const std::string& stream, std::uint64_t id, const Eigen::Isometry3d& pose,
           std::int64_t offset_ns) {
    KeyframeNode n;
    n.key = {stream, id};
    n.stamp.nanoseconds = static_cast<std::int64_t>(id) * 100000000 + offset_ns;
    n.pose = n.odom_pose = pose;
    n.descriptor.ring_key.assign(20, 0.0f);
    graph.add(std::move(n));
  }

  std::uint32_t node(const std::string& stream, std::uint64_t id) const {
    return static_cast<std::uint32_t>(graph.find({stream, id}));
  }

  /// The loop from a's keyframe `ia` to b's keyframe `ib` as registration measures it (true
  /// relative pose), times `error` (on the right: in a's keyframe's frame).
  MergeCandidate loop(std::uint64_t ia, std::uint64_t ib,
                      const Eigen::Isometry3d& error = Eigen::Isometry3d::Identity()) const {
    MergeCandidate c;
    c.from = node("a", ia);
    c.to = node("b", ib);
    c.edge.from = {"a", ia};
    c.edge.to = {"b", ib};
    const Eigen::Isometry3d truth_a = planar(2.0 * ia, 0.0, 0.0);
    const Eigen::Isometry3d truth_b = planar(2.0 * ib, 0.0, 0.0);
    c.edge.relative = truth_a.inverse() * truth_b * error;
    return c;
  }

  KeyframeGraph graph;
  Eigen::Isometry3d b_frame;
};

}  // namespace

TEST_F(MergeConfirmationTest, DisagreementOfTwoTrueLoopsIsZeroAndOfAnAliasItsError) {
  const MergeDisagreement same = merge_disagreement(loop(10, 11), loop(60, 60), graph);
  EXPECT_NEAR(same.separation, 100.0, 1e-9);
  EXPECT_NEAR(same.translation, 0.0, 1e-9);
  EXPECT_NEAR(same.rotation_deg, 0.0, 1e-6);
  // An alias that puts b's keyframe turned by 90 degrees: the rotation disagrees by 90.
  const MergeDisagreement alias =
      merge_disagreement(loop(10, 11), loop(60, 60, planar(0.0, 0.0, 90.0)), graph);
  EXPECT_NEAR(alias.rotation_deg, 90.0, 1e-6);
  // The earlier loop may be given with its ends the other way round (b's keyframe first).
  MergeCandidate reversed = loop(10, 11);
  std::swap(reversed.from, reversed.to);
  std::swap(reversed.edge.from, reversed.edge.to);
  reversed.edge.relative = reversed.edge.relative.inverse();
  const MergeDisagreement r = merge_disagreement(reversed, loop(60, 60), graph);
  EXPECT_NEAR(r.translation, 0.0, 1e-9);
  EXPECT_NEAR(r.separation, 100.0, 1e-9);
}

TEST_F(MergeConfirmationTest, OneLoopWaitsAndASecondAgreeingOneAtAnotherPlaceConfirms) {
  PlaceRecognitionConfig config;  // merge_confirmations 2, 50 m apart
  MergeConfirmation merges(config);
  EXPECT_TRUE(merges.offer(loop(10, 10), graph).empty());
  EXPECT_EQ(merges.pending(), 1u);
  // 10 m further on: too close to confirm (one look-alike place seen twice).
  EXPECT_TRUE(merges.offer(loop(15, 15), graph).empty());
  EXPECT_EQ(merges.pending(), 2u);
  // 1 m and 0.5 degrees off (within the agreement) and 56 m from the first: confirms it.
  const std::vector<MergeCandidate> confirmed =
      merges.offer(loop(38, 38, planar(1.0, 0.0, 0.5)), graph);
  ASSERT_EQ(confirmed.size(), 2u);
  EXPECT_EQ(confirmed[0].edge.from.id, 10u);
  EXPECT_EQ(confirmed[1].edge.from.id, 38u);
  EXPECT_EQ(merges.pending(), 1u);  // the second loop (46 m from the third) stays
}

TEST_F(MergeConfirmationTest, AContradictingLoopConfirmsNothing) {
  PlaceRecognitionConfig config;
  MergeConfirmation merges(config);
  // A wrong match: b's keyframe 60 found at a's keyframe 10, turned by 90 degrees.
  EXPECT_TRUE(merges.offer(loop(10, 60, planar(0.0, 0.0, 90.0)), graph).empty());
  // The true loops elsewhere contradict it: the first waits, the second confirms the first.
  EXPECT_TRUE(merges.offer(loop(70, 70), graph).empty());
  EXPECT_EQ(merges.pending(), 2u);
  const std::vector<MergeCandidate> confirmed = merges.offer(loop(40, 40), graph);
  ASSERT_EQ(confirmed.size(), 2u);
  EXPECT_EQ(confirmed[0].edge.from.id, 70u);
  EXPECT_EQ(confirmed[1].edge.from.id, 40u);
}

TEST_F(MergeConfirmationTest, OneConfirmationMergesAtTheFirstLoop) {
  PlaceRecognitionConfig config;
  config.merge_confirmations = 1;
  MergeConfirmation merges(config);
  EXPECT_EQ(merges.offer(loop(10, 10), graph).size(), 1u);
  EXPECT_EQ(merges.pending(), 0u);
}

TEST_F(MergeConfirmationTest, PendingLoopsWhoseGroupsWereJoinedAreDropped) {
  PlaceRecognitionConfig config;
  MergeConfirmation merges(config);
  EXPECT_TRUE(merges.offer(loop(10, 10), graph).empty());
  graph.groups().join(graph.groups().index("a"), graph.groups().index("b"));
  // A third stream c meets a: the pending a-b loop is dropped, not compared.
  add("c", 0, planar(0.0, 0.0, 0.0), 2000000000);
  add("c", 1, planar(2.0, 0.0, 0.0), 2000000000);
  MergeCandidate c;
  c.from = node("a", 0);
  c.to = node("c", 1);
  c.edge.from = {"a", 0};
  c.edge.to = {"c", 1};
  c.edge.relative = planar(2.0, 0.0, 0.0);
  EXPECT_TRUE(merges.offer(c, graph).empty());
  EXPECT_EQ(merges.pending(), 1u);
}

TEST(MergeConfirmationConfig, InvalidValuesAreRejected) {
  auto rejects = [](auto change) {
    MapperConfig c;
    change(c.place);
    EXPECT_ANY_THROW(validate(c));
  };
  rejects([](PlaceRecognitionConfig& p) { p.merge_confirmations = 0; });
  rejects([](PlaceRecognitionConfig& p) { p.merge_min_separation = -1.0; });
  rejects([](PlaceRecognitionConfig& p) { p.merge_agreement_m = 0.0; });
  rejects([](PlaceRecognitionConfig& p) { p.merge_agreement_per_m = -0.1; });
  rejects([](PlaceRecognitionConfig& p) { p.merge_agreement_deg = 200.0; });
  rejects([](PlaceRecognitionConfig& p) { p.loop_spacing = -1.0; });
  MapperConfig ok;
  EXPECT_NO_THROW(validate(ok));
}

TEST_F(MergeConfirmationTest, RestoredPendingLoopsConfirmAsTheOriginalsWould) {
  // A restart: the pending loop comes back from the store and the second agreeing loop
  // confirms the merge with it, as without the restart.
  PlaceRecognitionConfig config;
  MergeConfirmation before(config);
  EXPECT_TRUE(before.offer(loop(10, 10), graph).empty());
  const std::uint64_t version = before.version();
  EXPECT_GT(version, 0u);
  MergeConfirmation after(config);
  after.restore({before.pending_loops().begin(), before.pending_loops().end()}, graph);
  ASSERT_EQ(after.pending(), 1u);
  const std::vector<MergeCandidate> confirmed =
      after.offer(loop(38, 38, planar(1.0, 0.0, 0.5)), graph);
  ASSERT_EQ(confirmed.size(), 2u);
  EXPECT_EQ(confirmed[0].edge.from.id, 10u);
  EXPECT_EQ(before.version(), version) << "nothing changed the original";
}

TEST_F(MergeConfirmationTest, RestoringDropsLoopsWhoseGroupsWereJoined) {
  PlaceRecognitionConfig config;
  MergeConfirmation merges(config);
  graph.groups().join(graph.groups().index("a"), graph.groups().index("b"));
  merges.restore({loop(10, 10)}, graph);
  EXPECT_EQ(merges.pending(), 0u);
}
