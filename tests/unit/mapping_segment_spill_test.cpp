#include "litamin2/mapping/segment_spill.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <random>
#include <string>
#include <vector>

namespace {

using namespace litamin2;
using namespace litamin2::mapping;

/// A segment of `keyframes` random keyframes (40 distributions each) at random poses.
SegmentVoxels random_segment(std::mt19937& rng, int keyframes) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  SegmentVoxels segment;
  for (int k = 0; k < keyframes; ++k) {
    std::vector<Distribution> distributions(40);
    for (Distribution& d : distributions) {
      d.mean = Eigen::Vector3d(20 * unit(rng), 20 * unit(rng), 2 * unit(rng));
      const Eigen::Vector3d axis(unit(rng), unit(rng), unit(rng));
      d.cov = 0.1 * Eigen::Matrix3d::Identity() + 0.05 * axis * axis.transpose();
      d.count = 3 + k;
    }
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(2.0 * k, unit(rng), 0.0);
    pose.linear() = Eigen::AngleAxisd(0.1 * unit(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    segment.apply(distributions, pose, 3.0, +1);
  }
  return segment;
}

void expect_identical(const SegmentVoxels& a, const SegmentVoxels& b) {
  ASSERT_EQ(a.voxels().size(), b.voxels().size());
  for (std::size_t i = 0; i < a.voxels().size(); ++i) {
    const SegmentVoxels::Voxel& x = a.voxels()[i];
    const SegmentVoxels::Voxel& y = b.voxels()[i];
    EXPECT_EQ(x.key, y.key);
    EXPECT_EQ(x.count, y.count);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(x.sum[j], y.sum[j]);
    for (int j = 0; j < 6; ++j) EXPECT_EQ(x.sum_sq[j], y.sum_sq[j]);
  }
}

TEST(MappingSegmentSpill, SegmentsReadBackBitForBitAndSlotsAreReused) {
  std::mt19937 rng(7);
  const std::string path = ::testing::TempDir() + "segment_spill_test-segments";
  SegmentSpill spill(path);
  // Unlinked at creation: nothing is left beside the store, whatever happens to the process.
  EXPECT_NE(::access(path.c_str(), F_OK), 0);

  std::vector<SegmentVoxels> segments;
  std::vector<SegmentSpill::Slot> slots;
  for (int i = 0; i < 20; ++i) {
    segments.push_back(random_segment(rng, 1 + i % 10));
    ASSERT_FALSE(segments.back().empty());
    slots.push_back(spill.write(segments.back(), {}));
  }
  for (std::size_t i = 0; i < segments.size(); ++i)
    expect_identical(spill.read(slots[i]), segments[i]);
  const std::uint64_t file = spill.file_bytes();
  std::uint64_t live = 0;
  for (const SegmentVoxels& s : segments) live += s.voxels().size() * sizeof(SegmentVoxels::Voxel);
  EXPECT_EQ(spill.live_bytes(), live);

  // Rewritten smaller: in place. Released, then a segment that fits: the freed slot.
  const SegmentVoxels smaller = random_segment(rng, 1);
  ASSERT_LE(smaller.voxels().size(), slots[9].capacity);
  const SegmentSpill::Slot in_place = spill.write(smaller, slots[9]);
  EXPECT_EQ(in_place.offset, slots[9].offset);
  expect_identical(spill.read(in_place), smaller);
  spill.release(slots[19]);
  const SegmentSpill::Slot reused = spill.write(random_segment(rng, 2), {});
  EXPECT_EQ(reused.offset, slots[19].offset);
  EXPECT_EQ(spill.file_bytes(), file);
  // A segment grown beyond its slot moves to the end; the others are untouched.
  const SegmentVoxels grown = random_segment(rng, 30);
  ASSERT_GT(grown.voxels().size(), slots[0].capacity);
  const SegmentSpill::Slot moved = spill.write(grown, slots[0]);
  EXPECT_EQ(moved.offset, file);
  expect_identical(spill.read(moved), grown);
  for (std::size_t i = 1; i < 19; ++i) {
    if (i != 9) expect_identical(spill.read(slots[i]), segments[i]);
  }
}

}  // namespace
