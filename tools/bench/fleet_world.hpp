#pragma once
// litamin2-fleet-bench's world: a cheap model of the simulator's city (not ray-cast). A grid
// of streets around square blocks, each block lined with buildings of random widths, setbacks
// and heights, poles and trees along the kerbs, on a gently undulating ground. Its surfaces
// are cut once into 3 m world voxels, each a normal distribution (mean, covariance, count);
// a keyframe's patch is the voxels within range of the sensor that face it (no other
// occlusion), moved into the sensor frame, with noise on the means and a share dropped at
// random, so two visits of one place never give the same patch: ~500 distributions, like the
// tracker's keyframes on simulated KITTI.

#include "litamin2/core/distribution.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <unordered_map>
#include <vector>

namespace litamin2::bench {

struct FleetWorldConfig {
  /// Blocks along x and y; streets at every multiple of block_size, from 0 to blocks.
  int blocks = 10;
  double block_size = 100.0;
  /// Patch range around the sensor, metres (ground only within ground_range).
  double range = 40.0;
  double ground_range = 25.0;
  /// Noise on a voxel mean, metres; share of voxels dropped per patch.
  double mean_noise = 0.03;
  double dropout = 0.1;
  unsigned seed = 1;
};

class FleetWorld {
 public:
  explicit FleetWorld(const FleetWorldConfig& config);

  /// The distributions seen from a sensor at `sensor` (world frame), in the sensor frame.
  std::vector<Distribution> patch(const Eigen::Isometry3d& sensor, std::mt19937& rng) const;

  const FleetWorldConfig& config() const { return config_; }
  /// World voxels in all.
  std::size_t voxels() const { return voxels_.size(); }

 private:
  struct Voxel {
    Distribution d;
    /// Outward normal of the surface (zero for the ground and poles: seen from anywhere).
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    bool ground = false;
  };
  void add_facade(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double height,
                  const Eigen::Vector2d& normal);
  void add_pole(const Eigen::Vector2d& at, double height);
  void add_ground();
  static std::int64_t cell_key(std::int64_t x, std::int64_t y) {
    return (x << 32) ^ (y & 0xffffffff);
  }
  double ground_z(double x, double y) const;

  FleetWorldConfig config_;
  std::vector<Voxel> voxels_;
  /// 10 m cells of voxel indices.
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace litamin2::bench
