#pragma once
/// The per-frame work of one stream: run its tracker on the scan, move the pose to the base
/// frame by the sensor extrinsic, publish odometry (and the keyframe's distributions) through
/// a ResultSink with the twist since the previous frame (core/frame_twist.hpp) when the frame
/// was registered, and record the statistics. Used as the stream's StreamScheduler::Processor.

#include "litamin2/core/tracker.hpp"
#include "litamin2/daemon/daemon_config.hpp"
#include "litamin2/daemon/frame.hpp"
#include "litamin2/daemon/result_sink.hpp"
#include "litamin2/daemon/stream_handover.hpp"
#include "litamin2/daemon/stream_stats.hpp"

#include <memory>
#include <optional>

namespace litamin2::daemon {

class StreamProcessor {
 public:
  /// Throws ConfigError if the stream's tracker config is invalid. `sink` and `stats` must
  /// outlive the processor.
  StreamProcessor(StreamConfig config, ResultSink& sink, StreamStats& stats);
  /// A stream taken over from another daemon (stream_handover.hpp): outputs in the seed's
  /// odometry frame, keyframe ids from the seed's; the tracker continues from the seed's map
  /// keyframes if it has any, else its outputs are moved by the origin at the first frame.
  StreamProcessor(StreamConfig config, ResultSink& sink, StreamStats& stats, HandoverSeed seed,
                  double max_extrapolation_s);

  /// Processes the next frame of the stream (frames must come in order, one at a time).
  void process(Frame& frame);

  const StreamConfig& config() const { return config_; }
  const Tracker& tracker() const { return *tracker_; }
  /// The id the next keyframe gets.
  std::uint64_t keyframes() const { return keyframes_; }
  /// The handover origin in use (after the first frame of a stream taken over without map
  /// patches).
  const std::optional<Eigen::Isometry3d>& origin() const { return origin_; }
  /// The stream was taken over with map patches: its tracker continues from them.
  bool continued() const { return continued_; }

 private:
  StreamConfig config_;
  bool has_extrinsic_;
  Eigen::Isometry3d extrinsic_inverse_;
  std::unique_ptr<Tracker> tracker_;
  ResultSink& sink_;
  StreamStats& stats_;
  std::uint64_t keyframes_ = 0;
  /// Handover: the seed until the first frame, then the origin O applied to every output.
  std::optional<HandoverSeed> seed_;
  double max_extrapolation_s_ = 0.0;
  std::optional<Eigen::Isometry3d> origin_;
  bool continued_ = false;
  /// The last frame's stamp (deskew's clock, Tracker::restart_clock).
  std::optional<Stamp> last_stamp_;
  /// The last frame's published (base) pose, for the twist.
  std::optional<Eigen::Isometry3d> last_pose_;
};

/// The pose of the base in the odometry frame (the base at the first scan) from the sensor's
/// pose in the first sensor frame: E * sensor_pose * E^-1 with E the sensor-in-base extrinsic
/// (its covariance: transform_left_covariance(covariance, E), core/so3.hpp).
Eigen::Isometry3d base_pose(const Eigen::Isometry3d& sensor_pose,
                            const Eigen::Isometry3d& extrinsic);

}  // namespace litamin2::daemon
