#pragma once
/// LiTAMIN2 odometry for one sensor stream: constant-velocity prediction, registration of the
/// scan's distributions to the keyframe map, keyframe decision and map update.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/keyframe.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/core/scan_filter.hpp"
#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/stamp.hpp"
#include "litamin2/core/tracker_config.hpp"
#include "litamin2/core/tracker_seed.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

namespace litamin2 {

/// Wall-clock time of each stage of one frame, milliseconds.
struct StageTimes {
  double voxelize_ms = 0.0;
  double register_ms = 0.0;
  double map_update_ms = 0.0;
  /// Moving the points by the motion within the sweep (DeskewConfig), all passes.
  double deskew_ms = 0.0;
  double total_ms() const { return voxelize_ms + register_ms + map_update_ms + deskew_ms; }
};

/// When a scan was taken: its stamp, the reference time of its per-point times
/// (PointCloud::times). Stamps of one stream must increase.
struct SweepTiming {
  Stamp stamp;
};

struct FrameResult {
  /// Sensor pose in the frame of the first scan.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Covariance of the pose in (phi, tau) coordinates of the left update, from the Hessian at
  /// convergence (2 sigma^2 H^-1 with sigma^2 the cost per residual degree of freedom); zero for
  /// the first frame.
  Matrix6d covariance = Matrix6d::Zero();
  /// This frame was added to the map.
  bool keyframe = false;
  /// Registration succeeded (false for the first frame and when it failed; the pose is then
  /// the constant-velocity prediction).
  bool registered = false;
  int iterations = 0;
  /// Times the scan was voxelised (1 + re-voxelisations after large corrections).
  int voxelizations = 0;
  /// The re-grid loop stopped because a re-voxelisation did not shrink the correction.
  bool regrid_stopped = false;
  /// Points dropped as self-hits (ScanFilterConfig).
  int self_hits = 0;
  /// Share of the source distributions matched as inliers (robust weight at least 1/2).
  double inlier_share = 0.0;
  /// The scan was registered again from other starts (RecoveryConfig); `recovered` if one of
  /// them fitted better than the prediction's.
  bool retried = false;
  bool recovered = false;
  /// Registrations from the other starts that the retry made (RecoveryConfig::ranked_starts).
  int retry_registrations = 0;
  /// Registrations from starts at speed that the second scan's start search made
  /// (RecoveryConfig::first_speeds; 0 on every other frame).
  int start_registrations = 0;
  /// A break was confirmed (RecoveryConfig::reset_ratio): the previous scan fitted nothing, and
  /// this one fits the map restarted from it, which replaced the map; this scan is registered
  /// to it and added to it.
  bool map_reset = false;
  /// The global x/y/yaw search ran (RecoveryConfig::global_search); `pose_found` if a
  /// registration from one of its candidates was kept (the velocity is then not learnt from
  /// this frame's motion, which spans the missing frames).
  bool pose_searched = false;
  bool pose_found = false;
  /// The velocity was not learnt from this frame (pose_found, or the motion was farther from
  /// the prediction than PredictionConfig::learn_max_error_m / _deg).
  bool velocity_kept = false;
  int source_distributions = 0;
  int correspondences = 0;
  /// The scan's points were moved by the motion within the sweep before registration
  /// (DeskewConfig enabled and the scan had per-point times, or they came from the azimuth).
  bool deskewed = false;
  StageTimes times;
};

class Tracker {
 public:
  /// Throws ConfigError if the config is invalid. A named config.sensor applies its preset
  /// here (to the keys not in config.explicit_keys); kAuto recognises the sensor from the first
  /// scan (sensor_preset.hpp) and applies its preset then.
  explicit Tracker(const TrackerConfig& config);
  ~Tracker();

  /// Estimates the pose of the next scan of the stream, as it is (config.deskew is not used).
  FrameResult process(const PointCloud& scan);
  /// The same, for a scan taken at `timing`: the constant-velocity prediction is the last
  /// motion scaled to the time since the last scan (config.prediction; with equal intervals,
  /// as process(scan) predicts it), and with config.deskew enabled, the scan's self-hits are
  /// dropped (in the frame of their firing) and its points then moved to the sensor frame at
  /// the stamp by the motion within the sweep (core/deskew.hpp); the pose is the sensor's at
  /// the stamp. Without deskew and with equal
  /// intervals it is process(scan), bit for bit. Throws std::invalid_argument (state unchanged) for
  /// a stamp not after the previous one or invalid per-point times (point_times_error).
  FrameResult process(const PointCloud& scan, const SweepTiming& timing);
  /// A scan that could not be read: the pose is extrapolated by the constant velocity (the
  /// previous frame's motion is kept over the gap), nothing is registered or added to the map.
  FrameResult skip_frame();
  /// The same for a scan taken at `timing`: extrapolated over its interval as process(scan,
  /// timing) predicts, which keeps a timed tracker's intervals in step (throws
  /// std::invalid_argument for a stamp not after the previous one).
  FrameResult skip_frame(const SweepTiming& timing);
  /// Forgets the last stamp, so that the next timed scan may have any stamp (a restarted
  /// publisher's clock); the motion is kept. The first scan after it is deskewed with the
  /// predicted motion only.
  void restart_clock() { has_stamp_ = false; }
  /// Continues another tracker's stream (tracker_seed.hpp): before the first scan only (throws
  /// std::logic_error after). The seed is applied when the first scan comes, once `sensor:
  /// auto` has chosen the preset (and so the voxel size): the map is built from the seed's
  /// keyframes of the map's voxel size (VoxelMap::add_distributions), the first scan is
  /// registered to it from `predicted`, and the constant-velocity model and deskew's first
  /// pass start from `velocity`.
  void continue_from(TrackerSeed seed);
  /// Seed keyframes used / not used (other voxel size) when the seed was applied.
  std::size_t seed_keyframes_used() const { return seed_used_; }
  std::size_t seed_keyframes_skipped() const { return seed_skipped_; }

  /// The map of distributions the next scan is registered to.
  const VoxelMap& map() const { return map_; }
  /// Distributions of the last processed scan, sensor frame.
  const std::vector<Distribution>& last_distributions() const { return source_; }
  /// The config in use: after the first scan with `sensor: auto`, the recognised sensor's.
  const TrackerConfig& config() const { return config_; }
  /// Self-hit cells learnt (ScanFilterConfig, EgoFilterMode::kAuto), 0 before they are decided.
  std::size_t ego_cells() const { return ego_.cells(); }
  std::size_t frames() const { return frames_; }
  /// The running inlier shares (RecoveryConfig), negative before the first registration: of
  /// every registered frame (the recovery's trigger), and of the frames that fit as usual (the
  /// reset's).
  /// The last motion, sensor frame (what the next scan is predicted with, scaled to its interval).
  const Eigen::Isometry3d& velocity() const { return velocity_; }
  double typical_inlier_share() const { return typical_share_; }
  double fitting_inlier_share() const { return fitting_share_; }

 private:
  bool is_keyframe(const Eigen::Isometry3d& pose) const;
  /// `share` is below RecoveryConfig::reset_ratio of the fitting share (a break, when no
  /// recovery start does better).
  bool below_fitting(double share) const;
  /// The scan without its self-hits (the scan itself when there is nothing to drop).
  const PointCloud& without_self_hits(const PointCloud& scan, int& dropped);
  /// The scan's per-point times as deskew takes them (config.deskew.time_source), or null
  /// when it has none to use.
  const std::vector<float>* point_times(const PointCloud& scan);
  /// Checks that `timing` follows the last stamp; returns the interval since, seconds (0 for
  /// the first).
  double interval_to(const SweepTiming& timing) const;
  /// The factor the last motion is scaled by to predict a scan `interval` seconds after the
  /// last one (PredictionConfig); 1 when off, before two frames, or for an equal interval.
  double prediction_scale(double interval) const;
  /// The constant-velocity motion to the next scan: the last one scaled by `motion_scale` (as
  /// it is, bit for bit, at 1).
  Eigen::Isometry3d predicted_motion(double motion_scale) const;
  /// process(scan) with the last motion scaled by `motion_scale` as the prediction (and the
  /// recovery's starts scaled alike). With `self_hits_removed` (their number), `scan` is
  /// already without its self-hits and is not filtered again.
  /// `interval_s`: seconds since the last scan (RecoveryConfig::first_speeds).
  FrameResult process_scaled(const PointCloud& scan, double motion_scale,
                             std::optional<int> self_hits_removed = std::nullopt,
                             double interval_s = 0.1);
  /// Where a scan's registration starts, and that registration when choosing the start
  /// already made it (then the voxeliser holds its grid voxels, and its times are in `spent`).
  struct RegistrationStart {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    std::optional<ScanRegistration> registered;
    /// Registrations from starts at speed made to choose it.
    int speed_registrations = 0;
  };
  /// Where the second scan's registration starts when no motion is known
  /// (RecoveryConfig::first_speeds): the first pose, or the first pose moved along the sensor's
  /// x axis at one of the speeds over `interval_s`, if registering `scan` (as it is voxelised,
  /// without self-hits) from there fits min_gain times better than from the first pose; the
  /// speeds are tried only when the registration from the first pose moved the scan less than
  /// first_speeds_max_travel, and the best-ranked one is registered unless that registration
  /// ended nearer it than the first pose (first_speeds_skip_reached). The prediction otherwise
  /// (with no registration). Adds the registrations' time to `spent`.
  RegistrationStart registration_start(const PointCloud& scan, double motion_scale,
                                       double interval_s, StageTimes& spent);
  /// The recovery's other starts for a scan predicted at `predicted` (motion_scales applied to
  /// the last motion scaled by `motion_scale`): in the configured order, or with ranked_starts
  /// in the order of their score against the map, best first, given the scan's distributions
  /// `source` (sensor frame). Adds the ranking's time to `spent_ms`.
  std::vector<Eigen::Isometry3d> retry_starts(const std::vector<Distribution>& source,
                                              const Eigen::Isometry3d& predicted,
                                              double motion_scale, double& spent_ms) const;
  /// The registration from `start`: the one registration_start made, or a new one.
  ScanRegistration register_from(const PointCloud& scan, RegistrationStart& start);
  /// Before the first scan: applies `sensor: auto`'s preset, then the pending seed (if any).
  void prepare_first_scan(const PointCloud& raw);
  void apply_seed(const TrackerSeed& seed);
  /// Sets frame_registration_ for this frame: sigma_cov_after_handover's Cov term for the
  /// first scan after a seed.
  void choose_frame_registration();
  /// Replaces the map (the first scan alone) by the first scan deskewed with `twist`.
  void rebuild_first_keyframe(const Twist& twist);
  /// Estimates the correction of `twist` with the pose from `pose` (sweep_motion.hpp) and, if
  /// found, adds it to `twist` and deskews `measured` into deskewed_ again.
  void correct_sweep_motion(const PointCloud& measured, const std::vector<float>& times,
                            const Eigen::Isometry3d& pose, Twist& twist, StageTimes& spent);

  TrackerConfig config_;
  /// config_.registration as this frame's registrations use it (choose_frame_registration).
  RegistrationConfig frame_registration_;
  /// The scan being processed is the first after apply_seed (a handover).
  bool seeded_scan_ = false;
  EgoLearner ego_;
  PointCloud filtered_;
  Voxelizer voxelizer_;
  VoxelMap map_;
  std::unique_ptr<CorrespondenceSearch> search_;
  /// After a frame that fitted below RecoveryConfig::reset_ratio of the fitting share: a map
  /// restarted from that frame alone, and its search (null otherwise).
  std::unique_ptr<VoxelMap> break_map_;
  std::unique_ptr<CorrespondenceSearch> break_search_;
  std::vector<Distribution> source_;
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d velocity_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d last_keyframe_ = Eigen::Isometry3d::Identity();
  std::size_t frames_ = 0;
  /// continue_from()'s seed until the first scan; whether the first scan was prepared.
  std::unique_ptr<TrackerSeed> pending_seed_;
  bool prepared_ = false;
  std::size_t seed_used_ = 0;
  std::size_t seed_skipped_ = 0;
  /// Running typical inlier share of registered frames (RecoveryConfig), negative before any.
  double typical_share_ = -1.0;
  /// The same over the registered frames that fit as usual (at least
  /// RecoveryConfig::trigger_ratio of it): what the reset compares with.
  double fitting_share_ = -1.0;
  /// Deskew state (tracker_timing.cpp): the last stamp, the interval before it (seconds, 0
  /// before two frames), times from the azimuth, and the corrected scan.
  bool has_stamp_ = false;
  Stamp last_stamp_;
  double last_interval_ = 0.0;
  std::vector<float> azimuth_times_;
  PointCloud deskewed_;
  /// The first scan as measured and its times, until the second scan's motion deskews it in
  /// hindsight (tracker_timing.cpp).
  PointCloud first_scan_;
  std::vector<float> first_times_;
};

/// The keyframe of a frame the tracker has just added to its map (frame.keyframe is true): the
/// sensor's pose in the odometry frame of the vehicle base, sensor_in_base * frame.pose, with
/// the covariance moved alike (identity, the default: the tracker's own, bit for bit), the
/// scan's distributions and the map's voxel size. litamin2d and litamin2-odometry build their
/// keyframes with it.
Keyframe make_keyframe(const Tracker& tracker, const FrameResult& frame, KeyframeKey key,
                       Stamp stamp,
                       const Eigen::Isometry3d& sensor_in_base = Eigen::Isometry3d::Identity());

}  // namespace litamin2
