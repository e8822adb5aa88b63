// Dropped frames: which frames are kept, and that the writer writes only those with their
// true times and ground truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/frame_selection.hpp"
#include "litamin2/sim/sequence_writer.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;
namespace io = litamin2::io;
namespace fs = std::filesystem;

TEST(SimFrameSelection, DropsFramesWithBoundedGaps) {
  sim::FrameDropOptions opt;
  opt.probability = 0.5;
  opt.max_gap = 3;
  const auto kept = sim::select_frames(1000, opt, 42);
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(kept.front(), 0u);
  for (std::size_t k = 1; k < kept.size(); ++k) {
    EXPECT_GT(kept[k], kept[k - 1]);
    EXPECT_LE(kept[k] - kept[k - 1], opt.max_gap + 1);
  }
  // About half are dropped (fewer, because of the gap limit).
  EXPECT_GT(kept.size(), 450u);
  EXPECT_LT(kept.size(), 600u);
  bool some_gap_of_max = false;
  for (std::size_t k = 1; k < kept.size(); ++k) some_gap_of_max |= kept[k] - kept[k - 1] == 4;
  EXPECT_TRUE(some_gap_of_max);
  EXPECT_EQ(sim::select_frames(1000, opt, 42), kept);  // same seed, same frames
  EXPECT_NE(sim::select_frames(1000, opt, 43), kept);
  EXPECT_EQ(sim::select_frames(10, sim::FrameDropOptions{}, 42).size(), 10u);
  opt.probability = 1.0;
  EXPECT_THROW(sim::select_frames(10, opt, 1), std::invalid_argument);
}

TEST(SimFrameSelection, DropsBurstsOfTheConfiguredLength) {
  sim::FrameDropOptions opt;
  opt.burst_probability = 0.05;
  opt.burst_min = 5;
  opt.burst_max = 12;
  const auto kept = sim::select_frames(2000, opt, 7);
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(kept.front(), 0u);
  std::size_t bursts = 0, shortest = 1000, longest = 0;
  for (std::size_t k = 1; k < kept.size(); ++k) {
    const std::size_t dropped = kept[k] - kept[k - 1] - 1;
    if (dropped == 0) continue;
    ++bursts;
    shortest = std::min(shortest, dropped);
    longest = std::max(longest, dropped);
  }
  // Without single drops every gap is one burst: lengths within 5..12, both ends reached.
  EXPECT_GT(bursts, 20u);
  EXPECT_EQ(shortest, opt.burst_min);
  EXPECT_EQ(longest, opt.burst_max);
  EXPECT_EQ(sim::select_frames(2000, opt, 7), kept);
  // With single drops as well, gaps can be longer than a burst, never shorter than one frame.
  opt.probability = 0.3;
  const auto both = sim::select_frames(2000, opt, 7);
  EXPECT_LT(both.size(), kept.size());
  opt.burst_min = 6;
  opt.burst_max = 5;
  EXPECT_THROW(sim::select_frames(10, opt, 1), std::invalid_argument);
  opt.burst_min = 0;
  opt.burst_max = 5;
  EXPECT_THROW(sim::select_frames(10, opt, 1), std::invalid_argument);
  opt.burst_min = 5;
  opt.burst_probability = 1.0;
  EXPECT_THROW(sim::select_frames(10, opt, 1), std::invalid_argument);
}

TEST(SimFrameSelection, WriterWritesOnlyTheKeptFrames) {
  const auto path = sim::builtin_trajectory("loop");
  const std::vector<Eigen::Isometry3d> poses(path.begin() + 30, path.begin() + 42);
  const sim::World world(path, 2);
  sim::Raycaster rc(world);
  sim::SequenceWriteOptions opt;
  opt.model = sim::LidarModel::vlp16();
  opt.velo_to_cam = sim::kitti_default_velo_to_cam();
  opt.frames = {0, 1, 3, 4, 7, 11};
  const fs::path dir = fs::path(LITAMIN2_BINARY_DIR) / "sim_test_output" / "dropped";
  fs::remove_all(dir);
  const auto result = sim::write_sequence(dir.string(), rc, poses, opt);
  EXPECT_EQ(result.frames, 6u);
  const io::ScanSequence seq(dir.string());
  ASSERT_EQ(seq.size(), 6u);
  const auto gt = seq.ground_truth_velo();
  ASSERT_TRUE(gt.has_value());
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR(seq.timestamp(k), 0.1 * opt.frames[k], 1e-9);
    const Eigen::Isometry3d want = poses[0].inverse() * poses[opt.frames[k]];
    EXPECT_LT(((*gt)[k].translation() - want.translation()).norm(), 1e-6) << k;
  }
  std::ifstream sources(dir / "source_frames.txt");
  std::size_t v = 0, n = 0;
  while (sources >> v) EXPECT_EQ(v, opt.frames[n++]);
  EXPECT_EQ(n, 6u);
  opt.frames = {0, 0, 2};
  EXPECT_THROW(sim::write_sequence(dir.string(), rc, poses, opt), std::invalid_argument);
}
