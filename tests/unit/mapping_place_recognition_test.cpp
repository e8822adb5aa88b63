// Place recognition and loop verification on a synthetic scene: the descriptor finds the yaw
// between two views of one place and tells it from another place; verification recovers the
// relative pose of two views several metres and tens of degrees apart, and rejects a wrong
// place.

#include "litamin2/core/voxelizer.hpp"
#include "litamin2/mapping/distribution_moments.hpp"
#include "litamin2/mapping/loop_verifier.hpp"
#include "litamin2/mapping/place_descriptor.hpp"
#include "support/scene_views.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::planar_pose;

using litamin2::testing::map_of;
using litamin2::testing::mirrored;
using litamin2::testing::view;

TEST(MappingPlaceDescriptor, FindsTheYawBetweenTwoViews) {
  const PointCloud scene = litamin2::testing::synthetic_scene(1);
  const PlaceRecognitionConfig config;
  const auto a = make_place_descriptor(view(scene, planar_pose(0, 0, 0)), config);
  for (double yaw : {30.0, -90.0, 180.0}) {
    const auto b = make_place_descriptor(view(scene, planar_pose(0.5, 0.3, yaw)), config);
    const DescriptorMatch match = match_descriptors(b, a);
    // The query (b) sits at `yaw` in a's frame; one sector is 6 degrees.
    double error = match.yaw * 180.0 / M_PI - yaw;
    error = std::remainder(error, 360.0);
    EXPECT_LE(std::abs(error), 6.0) << "yaw " << yaw << " found " << match.yaw * 180.0 / M_PI;
    EXPECT_LT(match.distance, 0.2) << "yaw " << yaw;
  }
  const auto other = make_place_descriptor(view(mirrored(scene), planar_pose(0, 0, 0)), config);
  const auto same = make_place_descriptor(view(scene, planar_pose(0.5, 0.3, 30)), config);
  EXPECT_LT(match_descriptors(same, a).distance, match_descriptors(other, a).distance);
  EXPECT_LT(ring_key_distance(same, a), 0.05);
}

TEST(MappingLoopVerifier, RecoversTheRelativePoseOfTwoViews) {
  const PointCloud scene = litamin2::testing::synthetic_scene(1);
  const PointCloud scene2 = litamin2::testing::synthetic_scene(2);  // other noise, same geometry
  const Eigen::Isometry3d candidate = planar_pose(0, 0, 0);
  const Eigen::Isometry3d query = planar_pose(3.0, -1.0, 25.0);
  const VoxelMap submap = map_of(view(scene, candidate));
  // The descriptor's yaw is known to within a sector.
  const LoopVerification v =
      verify_loop(view(scene2, query), submap, planar_pose(0, 0, 22.0), LoopVerificationConfig{});
  ASSERT_TRUE(v.accepted) << v.reason << " at\n" << v.relative.matrix();
  const Eigen::Isometry3d truth = candidate.inverse() * query;
  EXPECT_LT((v.relative.translation() - truth.translation()).norm(), 0.1);
  EXPECT_LT(Eigen::AngleAxisd(v.relative.rotation().transpose() * truth.rotation()).angle() *
                180.0 / M_PI,
            0.3);
  EXPECT_GT(v.fitness, 0.7);
}

TEST(MappingLoopVerifier, RejectsAnotherPlace) {
  const PointCloud scene = litamin2::testing::synthetic_scene(1);
  const VoxelMap submap = map_of(view(scene, planar_pose(0, 0, 0)));
  const LoopVerification v = verify_loop(view(mirrored(scene), planar_pose(0, 0, 0)), submap,
                                         planar_pose(0, 0, 0), LoopVerificationConfig{});
  EXPECT_FALSE(v.accepted) << "fitness " << v.fitness << " rmse " << v.rmse;
  EXPECT_FALSE(v.reason.empty());
  EXPECT_LT(v.fitness, 0.5) << "a wrong place should be far below the 0.6 gate";
}
