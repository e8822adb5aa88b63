#pragma once
/// Sensor patterns of the simulated spinning LiDARs (beam elevations, azimuth resolution, range
/// limits, noise) with presets for the Velodyne HDL-64E (KITTI), Velodyne VLP-16 and a
/// 128-beam Ouster-like sensor.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::sim {

/// A spinning multi-beam LiDAR. Rays leave the sensor origin; the sensor frame is x forward,
/// y left, z up (KITTI's Velodyne frame).
struct LidarModel {
  /// Preset name ("hdl64", "vlp16", "os128") or a user label.
  std::string name;
  /// Elevation of each beam in degrees (positive up), one entry per beam (ring).
  std::vector<double> elevations_deg;
  /// Azimuth steps per revolution (rays per beam per scan).
  int azimuth_steps = 2048;
  /// Returns closer than this are discarded (ego vehicle), metres.
  double min_range = 2.5;
  /// Hard maximum range, metres.
  double max_range = 120.0;
  /// Range noise standard deviation, metres.
  double range_noise_sigma = 0.02;
  /// Probability that any return is lost independently of the surface.
  double dropout = 0.01;
  /// Range at which a reflectivity-1 target hit head-on gives the detection-threshold power;
  /// weaker echoes (dark, grazing or far surfaces) are lost with rising probability.
  double reference_range = 220.0;
  /// Height of the sensor's origin above the road, metres (KITTI: 1.73).
  double mount_height = 1.73;
  /// Ego vehicle as an axis-aligned box in the sensor frame (min, max corners): rays that hit it
  /// give no return (KITTI's car body hides part of the lowest beams). Empty if min > max.
  Eigen::Vector3d ego_box_min = Eigen::Vector3d(-1.8, -0.8, -1.73);
  /// Upper corner of the ego-vehicle box.
  Eigen::Vector3d ego_box_max = Eigen::Vector3d(1.2, 0.8, -0.5);

  /// Throws std::invalid_argument for no beams, an elevation outside [-90, 90] degrees, fewer
  /// than 8 azimuth steps, ranges with 0 <= min < max not holding, a negative noise, dropout
  /// outside [0, 1] or a mount height <= 0.
  void validate() const;

  /// Number of beams (rings).
  std::size_t beams() const { return elevations_deg.size(); }
  /// Rays cast per scan (beams x azimuth steps).
  std::size_t rays_per_scan() const { return beams() * static_cast<std::size_t>(azimuth_steps); }

  /// Velodyne HDL-64E as mounted on the KITTI car: 64 beams from +2.0 to -24.9 degrees
  /// (upper block 1/3 degree spacing, lower block 1/2 degree), 2048 azimuth steps, 120 m.
  static LidarModel hdl64();
  /// Velodyne VLP-16: 16 beams -15..+15 degrees every 2 degrees, 1800 steps, 100 m.
  static LidarModel vlp16();
  /// 128-beam sensor (Ouster OS-1/OS-2-like): uniform -22.5..+22.5 degrees, 2048 steps, 120 m.
  static LidarModel os128();
  /// Preset by name ("hdl64", "vlp16", "os128"); std::nullopt for an unknown name.
  static std::optional<LidarModel> from_name(const std::string& name);
  /// Names accepted by from_name.
  static std::vector<std::string> preset_names();
};

}  // namespace litamin2::sim
