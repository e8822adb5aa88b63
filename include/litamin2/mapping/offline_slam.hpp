#pragma once
/// Offline SLAM on one recorded sequence (`litamin2-odometry --loop-closure`): the tracker's
/// keyframes go to the aggregator's mapping back end in process as they are made, verified
/// loops are optimised at once, and in the end every frame's pose is corrected by the
/// correction of its latest keyframe.

#include "litamin2/core/stamp.hpp"
#include "litamin2/core/tracker.hpp"
#include "litamin2/mapping/mapper.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace litamin2::mapping {

class OfflineSlam {
 public:
  /// The stream name the keyframes are given in the mapper.
  static constexpr const char* kStream = "odometry";

  /// Throws ConfigError if the config is invalid.
  explicit OfflineSlam(const MapperConfig& config);

  /// Takes the next frame of the sequence as the tracker returned it; a keyframe
  /// (frame.keyframe) is added to the mapper (make_keyframe) and the graph optimised if it
  /// closed a loop.
  void add(const Tracker& tracker, const FrameResult& frame, Stamp stamp);

  /// The odometry poses of every frame added (in order) corrected by the optimised keyframes.
  std::vector<Eigen::Isometry3d> corrected(const std::vector<Eigen::Isometry3d>& odometry);

  /// A loop between two keyframes, by the indices of their frames (counted from the first
  /// frame added).
  struct Loop {
    std::size_t from_frame = 0;
    std::size_t to_frame = 0;
    double fitness = 0.0;
    double rmse = 0.0;
  };
  std::vector<Loop> loops() const;

  const Mapper& mapper() const { return mapper_; }
  /// Wall-clock time spent in the mapper, milliseconds.
  double milliseconds() const { return milliseconds_; }

 private:
  Mapper mapper_;
  std::uint64_t next_id_ = 0;
  /// For each frame, the id of the latest keyframe at or before it.
  std::vector<std::uint64_t> keyframe_of_frame_;
  /// For each keyframe id, its frame index.
  std::vector<std::size_t> frame_of_keyframe_;
  double milliseconds_ = 0.0;
};

}  // namespace litamin2::mapping
