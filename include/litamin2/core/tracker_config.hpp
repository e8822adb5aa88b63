#pragma once
/// Everything a LiTAMIN2 tracker is configured by, in one struct, and its validation (read from
/// YAML by config/tracker_config_yaml.hpp).

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/deskew.hpp"
#include "litamin2/core/global_pose_search.hpp"
#include "litamin2/core/registration_config.hpp"
#include "litamin2/core/scan_filter.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <set>
#include <string>
#include <vector>

namespace litamin2 {

/// The LiDAR a config is for (sensor_preset.hpp): a preset sets the parameters that depend on
/// it; kAuto recognises it from the first scan; kNone keeps every value as configured.
enum class SensorModel { kAuto, kNone, kHdl64, kHdl32, kVlp16, kOs1_64, kOs128 };

struct KeyframeConfig {
  /// A frame that moved this far from the last keyframe becomes a keyframe, metres.
  double distance = 2.0;
  /// ... or that turned this much, degrees.
  double angle_deg = 5.0;
};

/// The constant-velocity prediction of each scan's pose (added to LiTAMIN2; core/motion_model.hpp).
struct PredictionConfig {
  /// For a timed scan (Tracker::process(scan, timing), as litamin2d and litamin2-odometry
  /// run), the last frame's motion is scaled to the time since the last scan: a scan after
  /// dropped files is predicted as far as the vehicle went, not one frame's motion on. At most
  /// this many times the last motion (a long gap is not extrapolated without bound; the
  /// recovery's global search handles breaks); 0: off, the last motion as it is (untimed
  /// process(scan) always predicts so).
  double max_interval_ratio = 5.0;
  /// A registered motion that differs from the prediction by more than this (metres, or
  /// degrees of rotation) is not taken as the new velocity: no vehicle changes its motion so much
  /// within a frame, so the frame spans missing ones (a break) or was registered wrongly, and
  /// the next scan is predicted with the velocity before it. 0: off (every motion is learnt).
  double learn_max_error_m = 0.0;
  double learn_max_error_deg = 0.0;
};

/// Recovery when the constant-velocity prediction is wrong (frames dropped or irregularly
/// spaced, docs/accuracy.md "Sparse sensors"): registration converges near where it starts, so a
/// scan that fits the map badly from the prediction is registered again from other starts.
struct RecoveryConfig {
  /// Off: the constant-velocity prediction is the only start.
  bool enabled = true;
  /// A registration whose inlier share (source distributions matched with a robust weight of at
  /// least 1/2) is below this fraction of the typical share of recent frames is retried.
  double trigger_ratio = 0.7;
  /// The other starts: the constant-velocity motion scaled by these factors (0: standing still,
  /// 2: one frame dropped).
  std::vector<double> motion_scales = {0.0, 0.5, 1.5, 2.0, 3.0};
  /// The starts are ranked by the correlative score of the scan against the map (PoseScorer:
  /// up to global_search.max_sources scan distribution means, blurred by the widest gap between
  /// neighbouring starts, as the second scan's starts at speed are ranked) and registered best
  /// first; after the best ranked_starts, the others are registered only if none of those was
  /// kept. A registration from a start far from the motion iterates to its caps, so registering
  /// every start made a retried frame cost several frames' time (docs/accuracy.md "Retries
  /// ranked by their score"). 0: every start is registered, in the configured order.
  int ranked_starts = 1;
  /// A registration from another start replaces the prediction's only if its inlier share is
  /// at least this multiple of the prediction's: where the scene constrains the motion weakly
  /// (a highway, a corridor) the starts fit almost alike, and the prediction is the better
  /// guess. 1: the best share wins. docs/accuracy.md "A start must fit clearly better".
  double min_gain = 1.15;
  /// The second scan, when no motion is known yet (a start at speed: a restarted daemon, a
  /// recording cut mid-drive), is also registered from the first pose moved along the sensor's
  /// x axis at these speeds (m/s) over the interval between the two scans (0.1 s untimed); one
  /// of them is kept if it fits at least min_gain times better than the start at rest. Empty:
  /// the start at rest only.
  std::vector<double> first_speeds = {5.0, 10.0, 20.0, 30.0};
  /// ... searched only when the registration from the first pose moved the scan less than
  /// this, metres: a start at speed sticks near rest, while a registration that travelled to
  /// a motion has found it (on the harder simulated starts the search changed nothing there,
  /// at 5-8x the second scan's time; docs/benchmarks.md). 0: always searched.
  double first_speeds_max_travel = 1.0;
  /// ... and the best-ranked start at speed is not registered when the registration from rest
  /// ended nearer that start than the first pose: it travelled more than half way to the
  /// motion the start stands for (the builtin loop's 0.8 m; docs/benchmarks.md). false: the
  /// best start is always registered.
  bool first_speeds_skip_reached = true;
  /// Weight of a new frame in the running inlier shares: the typical share (every registered
  /// frame; the trigger above and the global search compare with it) and the fitting share
  /// (only frames at or above trigger_ratio of it: a run of frames that fit badly, after a
  /// break or on a map spoilt by one, does not lower it; reset_ratio compares with it).
  double share_smoothing = 0.1;
  /// A scan whose best inlier share after the retries and the global search is below this
  /// fraction of the fitting share is a suspected break in the input (consecutive files not
  /// related by any motion the registration finds: many frames missing, a scene cut). It is
  /// kept as usual, and a second map is started from it alone. If the next scan also fits the
  /// map below this fraction, it is registered to that second map too, and if it fits there
  /// at least trigger_ratio of the fitting share, the break is confirmed: the old map, which
  /// may no longer be where it is drawn, is dropped for the second one (FrameResult::
  /// map_reset). A scan that fits badly for another reason (clutter, a view the map has not
  /// seen) is followed by one that fits the old map, and nothing is dropped. Without it, a scan
  /// registered to a wrong pose stays in the map, and the scans after it are matched to a map
  /// holding the scene twice. 0: off (default); the vlp16 preset sets 0.5. On the real VLP-16
  /// drive consecutive files agree under no rigid motion on many frames (docs/accuracy.md,
  /// "Breaks in the real VLP-16 drive", "Breaks that cannot be registered").
  double reset_ratio = 0.0;
  /// A wider search after the retries (global_pose_search.hpp): a scan whose best share is still
  /// below global_search.trigger_ratio of the typical share is located by a correlative x/y/yaw
  /// search against the map and registered from the best candidates; if none fits, the reset
  /// above applies. Runs before the reset; on by default (trigger_ratio 0.5).
  GlobalPoseSearchConfig global_search;
};

struct TrackerConfig {
  /// Which sensor preset applies (to the keys not in explicit_keys).
  SensorModel sensor = SensorModel::kAuto;
  /// Points dropped before voxelisation (self-hits).
  ScanFilterConfig filter;
  /// Scan voxelisation; the map uses the same voxel size, point limits and regularisation.
  VoxelizerConfig voxelizer;
  /// Map extent.
  VoxelMapConfig map;
  /// The solver.
  RegistrationConfig registration;
  /// When the map is updated.
  KeyframeConfig keyframe;
  PredictionConfig prediction;
  /// Other starts when the prediction fits badly.
  RecoveryConfig recovery;
  /// Dotted keys set explicitly (by a config file or a command-line option): a sensor preset
  /// leaves them as they are.
  std::set<std::string> explicit_keys;
  /// Motion compensation within the sweep (Tracker::process with a SweepTiming).
  DeskewConfig deskew;
};

/// Throws ConfigError on the first invalid value.
void validate(const TrackerConfig& config);

}  // namespace litamin2
