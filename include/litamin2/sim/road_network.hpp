#pragma once
/// The roads of a simulated World: the sensor trajectories resampled every few metres, indexed
/// on a grid for distance queries, each stretch with its district, and the height of the road
/// surface below them. Part of the World builder; immutable after construction.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "litamin2/sim/world.hpp"
#include "litamin2/sim/world_object.hpp"

namespace litamin2::sim {

/// One sample of a road: a sensor pose kept every kSampleSpacing metres of a trajectory.
struct PathSample {
  /// Sensor position (world frame).
  Eigen::Vector3d p;
  /// Unit heading in the plane.
  Eigen::Vector2d t;
  /// Speed around the sample (over +-10 frames at 10 Hz), m/s.
  double speed = 0.0;
  /// Arc length along the trajectory, metres.
  double arc = 0.0;
  /// Index of the trajectory.
  int path = 0;
  /// Index of the next sample of the same trajectory, -1 at its end.
  int next = -1;
  /// Character of the stretch.
  District district = District::kUrban;
};

/// The sampled trajectories (roads) with their districts.
class RoadNetwork {
 public:
  /// Metres between path samples.
  static constexpr double kSampleSpacing = 2.0;
  /// Cell size of the sample index, metres.
  static constexpr double kCell = 8.0;
  /// Spacing of the lattice road_height() interpolates, metres.
  static constexpr double kLattice = 4.0;

  /// Samples the sensor trajectories and assigns districts along them (random stretch lengths
  /// and kinds drawn from `seed`; fast stretches are open). No trajectory poses: empty().
  RoadNetwork(const std::vector<std::vector<Eigen::Isometry3d>>& paths, std::uint64_t seed,
              const WorldOptions& options);

  /// True if there is no sample (no trajectory pose was given).
  bool empty() const { return samples_.empty(); }
  /// Number of trajectories.
  std::size_t path_count() const { return path_samples_.size(); }
  /// Sample indices of trajectory p, in driving order.
  const std::vector<int>& path(int p) const { return path_samples_[p]; }
  /// Sample i.
  const PathSample& sample(int i) const { return samples_[i]; }

  /// Nearest road segment within max_d of (x, y): (distance, index of the segment's first
  /// sample), or (max_d, -1) if there is none.
  std::pair<double, int> nearest(double x, double y, double max_d) const;
  /// District of the road nearest to (x, y) within 200 m, urban if there is none.
  District district_near(double x, double y) const;

  /// Point at arc length `a` of path p: position, unit heading and district. False if `a` is
  /// outside the path.
  bool at_arc(int p, double a, Eigen::Vector2d& pos, Eigen::Vector2d& tan, District& dist) const;

  /// Road height (sensor height below the trajectories) at (x, y), exact: a Gaussian-weighted
  /// local plane fit over nearby samples.
  double road_height_raw(double x, double y) const;
  /// road_height_raw interpolated bilinearly on a kLattice grid (smooth and cheap).
  double road_height(double x, double y) const;

  /// Keys (cell_key) of the tiles within corridor_radius of the roads: the tiles with ground.
  std::unordered_set<std::int64_t> corridor_tiles() const;

 private:
  void add_samples(const std::vector<std::vector<Eigen::Isometry3d>>& paths);
  void assign_districts(std::uint64_t seed);

  WorldOptions opt_;
  std::vector<PathSample> samples_;
  /// Sample indices per path, in order.
  std::vector<std::vector<int>> path_samples_;
  /// Sample indices by kCell cell.
  std::unordered_map<std::int64_t, std::vector<int>> grid_;
  /// Longest distance between consecutive samples of a path.
  double max_segment_ = kSampleSpacing;
};

}  // namespace litamin2::sim
