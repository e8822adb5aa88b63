#pragma once
/// Several LiDARs of one vehicle as one stream: the scans of the listed sensors, each moved
/// into the vehicle's base frame by its extrinsic (sensor pose in the base frame), merged by
/// header stamp into one Frame for the stream's tracker. Pure logic: no threads, no DDS (the
/// daemon serialises calls, DaemonNode).
///
/// A merged frame holds at most one scan of each sensor, and the stamps of its scans lie
/// within `window_s` of each other. It is emitted
///  - when every sensor has delivered its scan (complete);
///  - when a scan arrives that cannot belong to it (stamped beyond the window, or a second scan
///    of a sensor already in it), or `timeout_s` after its first scan arrived (expire()), with
///    the scans that arrived: each missing sensor is counted (SensorMergeCounters::missing).
/// A scan is rejected and counted when it is stamped at or before its sensor's last accepted
/// scan (out_of_order), or when it belongs to a frame already emitted: at or before that frame's
/// newest scan, or, for a sensor missing from it, within its window (before the scan that
/// closed it), or more than the window before the pending frame's newest scan (late). A merged
/// frame's stamp only moves forward.
///
/// The merged frame's stamp is the earliest stamp among its scans; its points are the scans'
/// points in the base frame, in the sensors' listed order (not arrival order); per-point times
/// are re-expressed relative to the merged stamp (time + scan stamp - merged stamp). When some
/// scan has per-point times, the points of a scan without them get its stamp's offset (the
/// moment deskew would take them at on their own); intensities are kept only when every scan
/// has them.

#include "litamin2/daemon/frame.hpp"

#include <Eigen/Geometry>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::daemon {

/// How the scans of a stream's sensors are merged.
struct ScanMergerConfig {
  /// Largest spread of the header stamps within one merged frame, seconds (about half the
  /// sensors' sweep period: 10 Hz sensors started together are a few ms apart).
  double window_s = 0.05;
  /// Seconds after a frame's first scan arrived (steady clock) after which it is emitted with
  /// the scans it has: bounds the latency a sensor that stops adds.
  double timeout_s = 0.2;
};

/// Why the merge config is invalid (std::nullopt when valid): window_s in (0, 0.5], timeout_s in
/// (0, 10], both finite.
std::optional<std::string> scan_merger_config_error(const ScanMergerConfig& config);

/// Why `extrinsic` is not a rigid transform (std::nullopt when it is): finite, orthonormal
/// rotation with determinant +1, last row 0 0 0 1.
std::optional<std::string> extrinsic_error(const Eigen::Isometry3d& extrinsic);

struct SensorMergeCounters {
  /// Scans accepted into a frame.
  std::uint64_t scans = 0;
  /// Merged frames emitted without this sensor's scan.
  std::uint64_t missing = 0;
  /// Scans stamped at or before this sensor's last accepted one.
  std::uint64_t out_of_order = 0;
  /// Scans too old for the pending frame, or of a frame already emitted.
  std::uint64_t late = 0;
};

struct ScanMergerCounters {
  /// Merged frames emitted.
  std::uint64_t frames = 0;
  /// Of these, frames with at least one sensor missing.
  std::uint64_t incomplete_frames = 0;
  /// One per sensor, in the listed order.
  std::vector<SensorMergeCounters> sensors;

  /// Scans rejected over all sensors (out_of_order + late).
  std::uint64_t rejected() const;
  /// Missing scans over all sensors.
  std::uint64_t missing() const;
};

class ScanMerger {
 public:
  using Clock = std::chrono::steady_clock;

  /// One extrinsic (sensor -> base) per sensor. Throws std::invalid_argument without sensors,
  /// with an extrinsic that is not rigid or an invalid config.
  ScanMerger(std::vector<Eigen::Isometry3d> extrinsics, ScanMergerConfig config);

  /// Takes a scan of sensor `sensor` (its cloud in the sensor frame, its stamp, its arrival);
  /// returns the merged frames this completes or closes (0, 1 or 2; in stamp order). Throws
  /// std::out_of_range for a sensor index beyond the list.
  std::vector<Frame> add(std::size_t sensor, Frame scan);
  /// The pending frame if its first scan arrived at least timeout_s before `now`.
  std::vector<Frame> expire(Clock::time_point now);
  /// The pending frame, whatever its age (at shutdown).
  std::vector<Frame> flush();
  /// Forgets the stamps seen (a publisher restarted its stamps: PointsListener starts over
  /// too); the pending frame is emitted first.
  std::vector<Frame> restart();

  std::size_t sensors() const { return extrinsics_.size(); }
  /// A frame has at least one scan and waits for the others.
  bool pending() const { return arrived_ > 0; }
  const ScanMergerCounters& counters() const { return counters_; }

 private:
  /// Emits the pending frame; `next`: the stamp of the scan that closes it by opening the
  /// next frame.
  Frame emit(std::optional<Stamp> next);

  std::vector<Eigen::Isometry3d> extrinsics_;
  std::int64_t window_ns_;
  Clock::duration timeout_;
  /// The pending frame's scans by sensor.
  std::vector<std::optional<Frame>> slots_;
  std::size_t arrived_ = 0;
  Stamp earliest_{}, newest_{};
  Clock::time_point first_arrival_{};
  /// Each sensor's last accepted stamp.
  std::vector<std::optional<Stamp>> last_stamp_;
  /// Per sensor, the stamp at or before which its scans are late (a frame they belong to was
  /// emitted).
  std::vector<std::optional<Stamp>> floor_;
  ScanMergerCounters counters_;
};

}  // namespace litamin2::daemon
