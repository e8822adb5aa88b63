#pragma once
/// The ego vehicle's own body as seen by its LiDAR: boxes fixed to the vehicle that return
/// points (self-hits), so those points stay fixed in the sensor frame while the world moves.
/// Real roof-mounted sensors see the roof, roof bars and mount 1-2 m away.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::sim {

/// One part of the body: an axis-aligned box in the vehicle frame centred on the sensor's
/// optical centre (x forward, y left, z up; the origin is the sensor, so the box must not
/// contain it).
struct BodyBox {
  /// Lower corner, metres.
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  /// Upper corner, metres.
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  /// Diffuse reflectivity of the part in [0, 1].
  float reflectivity = 0.3f;
};

/// Where a ray from the sensor meets the body.
struct BodyHit {
  /// Distance from the sensor along the unit ray, metres.
  double range = 0.0;
  /// Outward normal of the face hit (one of +-x, +-y, +-z).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// Reflectivity of the part hit.
  float reflectivity = 0.3f;
};

/// The body: any number of boxes (none = no self-hits).
struct EgoBody {
  /// The parts, in the vehicle frame.
  std::vector<BodyBox> boxes;

  /// True if there are no parts.
  bool empty() const { return boxes.empty(); }
  /// Nearest hit of the ray from the sensor origin along `direction` (unit, vehicle frame).
  std::optional<BodyHit> intersect(const Eigen::Vector3d& direction) const;
  /// Throws std::invalid_argument for a box with min >= max on an axis, a non-finite corner,
  /// a box containing the sensor origin, a reflectivity outside [0, 1] or a part farther than
  /// 10 m from the sensor.
  void validate() const;

  /// No body.
  static EgoBody none();
  /// The roof of a car with two roof bars and a rear mount rail behind a roof-mounted sensor,
  /// fitted to a real VLP-16 drive: returns 1.0-1.8 m behind the sensor, 0.15-0.37 m below
  /// it, within about +-35 degrees of straight back.
  static EgoBody roof_rack();
  /// Preset by name ("none", "roof-rack"); std::nullopt for an unknown name.
  static std::optional<EgoBody> from_name(const std::string& name);
  /// Names accepted by from_name.
  static std::vector<std::string> preset_names();
};

}  // namespace litamin2::sim
