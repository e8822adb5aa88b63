// The SSE2 voting kernel against the portable double loop: same voxels, same counts (but for
// points within float rounding of a voxel face), same moments to float accuracy; and the
// dispatch falls back to the portable loop where local keys would not fit; and the AVX2 keying
// step gives the SSE2 one's keys and offsets bit for bit.

#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxel_keying.hpp"
#include "litamin2/core/voxel_voting.hpp"
#include "litamin2/io/kitti_bin.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <tuple>

namespace litamin2 {
namespace {

using VoxelTable = std::map<std::tuple<int, int, int>, VoxelMoments>;

/// Votes with `vote` into a table keyed by voxel index (moments about the voxel centre).
template <class Vote>
VoxelTable vote_into_table(const PointCloud& cloud, const Eigen::Isometry3d& pose,
                           const VoxelizerConfig& config, Vote vote) {
  VoxelTable table;
  vote(cloud.points.data(), cloud.points.data() + cloud.points.size(), pose, config,
       [&](const VoxelIndex& index) -> VoxelMoments& {
         auto [it, inserted] = table.try_emplace({index.x(), index.y(), index.z()});
         if (inserted) {
           it->second.origin =
               (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * config.voxel_size;
         }
         return it->second;
       });
  return table;
}

VoxelTable vote_scalar(const PointCloud& cloud, const Eigen::Isometry3d& pose,
                       const VoxelizerConfig& config) {
  return vote_into_table(cloud, pose, config, [](auto... args) { vote_points_scalar(args...); });
}

VoxelTable vote_dispatched(const PointCloud& cloud, const Eigen::Isometry3d& pose,
                           const VoxelizerConfig& config) {
  return vote_into_table(cloud, pose, config, [](auto... args) { vote_points(args...); });
}

/// Compares the two tables: every voxel of one is in the other, at most `max_moved` points in
/// another voxel in total, and voxels with equal counts have the same mean and covariance up to
/// the kernel's float rounding: a point at 100 m is moved with an error of ~1e-5 m, which moves
/// a covariance entry by about 2 x 1.5 m x 1e-5 m / sqrt(n). A flat voxel's variance along its
/// normal is 4e-4 m^2 for 2 cm range noise, so the bounds are well below what the cost sees.
void expect_same_voxels(const VoxelTable& expected, const VoxelTable& actual, int max_moved) {
  int moved = 0;
  int compared = 0;
  for (const auto& [index, e] : expected) {
    const auto it = actual.find(index);
    if (it == actual.end()) {
      moved += e.count;
      continue;
    }
    const VoxelMoments& a = it->second;
    if (a.count != e.count) {
      moved += std::abs(a.count - e.count);
      continue;
    }
    ++compared;
    const double n = e.count;
    const Eigen::Vector3d mean_e = e.sum / n, mean_a = a.sum / n;
    EXPECT_LT((mean_e - mean_a).norm(), 2e-5) << "voxel mean, count " << e.count;
    const Eigen::Matrix3d cov_e = e.second_moment() / n - mean_e * mean_e.transpose();
    const Eigen::Matrix3d cov_a = a.second_moment() / n - mean_a * mean_a.transpose();
    EXPECT_LT((cov_e - cov_a).cwiseAbs().maxCoeff(), 2e-5) << "voxel covariance, count " << e.count;
  }
  for (const auto& [index, a] : actual) {
    if (expected.find(index) == expected.end()) moved += a.count;
  }
  EXPECT_LE(moved, max_moved);
  EXPECT_GT(compared, 0);
}

Eigen::Isometry3d far_pose() {
  // Far from the origin and turned, as a pose late in a long drive.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = so3_exp(Eigen::Vector3d(0.02, -0.03, 2.1));
  pose.translation() = Eigen::Vector3d(-3571.37, 1234.56, -41.2);
  return pose;
}

TEST(VoxelVoting, Sse2KernelMatchesScalarOnRealScan) {
  const std::string path = LITAMIN2_SHARED_DATA_DIR "/kitti/seq00_frames_xyz/000000.bin";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared KITTI data not found: " << path;
  const PointCloud scan = io::read_kitti_bin(path);
  VoxelizerConfig config;
  ASSERT_TRUE(sse2_voting::fits(config));
  for (const Eigen::Isometry3d& pose : {Eigen::Isometry3d::Identity(), far_pose()}) {
    // Float coordinates put a point within ~1e-5 m of a voxel face on either side: a handful
    // of 124k points may change voxel.
    expect_same_voxels(vote_scalar(scan, pose, config), vote_dispatched(scan, pose, config), 20);
  }
}

TEST(VoxelVoting, Sse2KernelDropsInvalidPointsAndHandlesTails) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coordinate(-60.f, 60.f);
  std::uniform_real_distribution<float> along(-0.01f, 0.01f);
  VoxelizerConfig config;
  config.voxel_size = 2.0;
  config.min_range = 2.0;
  config.max_range = 50.0;
  // Sizes around the kernel's groups of 4 and blocks of 256.
  for (std::size_t size : {0, 1, 3, 4, 5, 255, 256, 257, 1023, 4099}) {
    PointCloud cloud;
    for (std::size_t i = 0; i < size; ++i) {
      // Runs of nearby points, as a scan's rings give, with invalid points mixed in.
      const Eigen::Vector3f base(coordinate(rng), coordinate(rng), 0.1f * coordinate(rng));
      const int run = 1 + static_cast<int>(i % 7);
      for (int k = 0; k < run && cloud.points.size() < size; ++k) {
        cloud.points.push_back(base + Eigen::Vector3f(along(rng), along(rng), along(rng)));
      }
      if (i % 13 == 0 && cloud.points.size() < size) {
        cloud.points.emplace_back(std::numeric_limits<float>::quiet_NaN(), 1.f, 1.f);
      }
      if (i % 17 == 0 && cloud.points.size() < size) {
        cloud.points.emplace_back(std::numeric_limits<float>::infinity(), 0.f, 0.f);
      }
      if (i % 19 == 0 && cloud.points.size() < size) cloud.points.emplace_back(0.5f, 0.f, 0.f);
    }
    cloud.points.resize(size);
    const VoxelTable expected = vote_scalar(cloud, far_pose(), config);
    const VoxelTable actual = vote_dispatched(cloud, far_pose(), config);
    int expected_points = 0, actual_points = 0;
    for (const auto& entry : expected) expected_points += entry.second.count;
    for (const auto& entry : actual) actual_points += entry.second.count;
    EXPECT_EQ(actual_points, expected_points) << size << " points";
    if (size > 100) expect_same_voxels(expected, actual, 2);
  }
}

TEST(VoxelVoting, FallsBackToScalarWhereLocalKeysDoNotFit) {
  VoxelizerConfig config;
  config.voxel_size = 0.1;
  config.max_range = 100.0;  // 1000 voxels from the sensor: beyond 10-bit local keys
  EXPECT_FALSE(sse2_voting::fits(config));
  PointCloud cloud;
  for (int i = 0; i < 1000; ++i) cloud.points.emplace_back(0.05f * i + 1.5f, 0.3f, -0.2f);
  const VoxelTable expected = vote_scalar(cloud, far_pose(), config);
  const VoxelTable actual = vote_dispatched(cloud, far_pose(), config);
  ASSERT_EQ(actual.size(), expected.size());
  for (const auto& [index, e] : expected) {
    const VoxelMoments& a = actual.at(index);
    EXPECT_EQ(a.count, e.count);
    EXPECT_EQ(a.sum, e.sum);  // the same double loop: bit-identical
    EXPECT_EQ(a.sum_sq, e.sum_sq);
  }
}

#if defined(LITAMIN2_HAVE_SSE2_VOTING)
TEST(VoxelKeying, Avx2MatchesSse2BitForBit) {
  using namespace sse2_voting;
  if (!cpu_has_avx2()) GTEST_SKIP() << "this CPU has no AVX2";
  std::mt19937 rng(5);
  std::normal_distribution<float> coordinate(0.0f, 30.0f);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> angle(0.0, 1.0);
  constexpr int kMax = 256;
  std::vector<Eigen::Vector3f> points(kMax);
  alignas(32) std::uint32_t keys_sse2[kMax], keys_avx2[kMax];
  alignas(32) float offsets_sse2[kMax][4], offsets_avx2[kMax][4];
  int valid = 0, invalid = 0;
  for (const float voxel_size : {0.5f, 3.0f}) {
    for (const int count : {0, 1, 3, 4, 5, 7, 8, 9, 15, 16, 17, 31, 255, 256}) {
      KeyingFrame frame;
      const Eigen::Matrix3f r =
          so3_exp(Eigen::Vector3d(angle(rng), angle(rng), angle(rng))).cast<float>();
      for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) frame.rotation[3 * row + col] = r(row, col);
        frame.translation[row] = static_cast<float>(unit(rng)) * voxel_size;
      }
      frame.voxel_size = voxel_size;
      frame.inv_voxel_size = 1.0f / voxel_size;
      frame.min_range_sq = 1.0f;
      frame.max_range_sq = 100.0f * 100.0f;
      for (int i = 0; i < count; ++i) {
        points[i] = Eigen::Vector3f(coordinate(rng), coordinate(rng), coordinate(rng));
        const double kind = unit(rng);  // some points the range test or NaN/inf must drop
        if (kind < 0.05)
          points[i].x() = std::numeric_limits<float>::quiet_NaN();
        else if (kind < 0.1)
          points[i].y() = std::numeric_limits<float>::infinity();
        else if (kind < 0.15)
          points[i] *= 0.01f;  // within min_range
        else if (kind < 0.2)
          points[i] *= 10.0f;  // mostly beyond max_range
      }
      std::memset(keys_sse2, 0, sizeof(keys_sse2));
      std::memset(keys_avx2, 0, sizeof(keys_avx2));
      key_block_sse2(points.data(), count, frame, keys_sse2, offsets_sse2);
      key_block_avx2(points.data(), count, frame, keys_avx2, offsets_avx2);
      for (int i = 0; i < count; ++i) {
        ASSERT_EQ(keys_avx2[i], keys_sse2[i]) << "point " << i << " of " << count;
        if (keys_sse2[i] == kInvalidKey) {
          ++invalid;
          continue;
        }
        ++valid;
        ASSERT_EQ(std::memcmp(offsets_avx2[i], offsets_sse2[i], sizeof(offsets_sse2[i])), 0)
            << "point " << i << " of " << count;
      }
      for (int i = count; i < kMax; ++i) {  // nothing written past count
        ASSERT_EQ(keys_sse2[i], 0u);
        ASSERT_EQ(keys_avx2[i], 0u);
      }
    }
  }
  EXPECT_GT(valid, 500);
  EXPECT_GT(invalid, 100);
}
#endif

}  // namespace
}  // namespace litamin2
