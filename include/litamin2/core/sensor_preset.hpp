#pragma once
/// Sensor presets: the tracker parameters that depend on the LiDAR (beam count and vertical
/// field of view), and the recognition of the sensor from a scan for `sensor: auto`.

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/tracker_config.hpp"

#include <optional>
#include <string>
#include <vector>

namespace litamin2 {

/// Rings and vertical field of view seen in one scan.
struct SensorSignature {
  /// Separate elevation peaks (beams) found; dense sensors whose beams blur into each other
  /// give fewer.
  int rings = 0;
  /// Lowest and highest beam elevation that held returns, degrees.
  double lowest_deg = 0.0;
  double highest_deg = 0.0;
  /// Points the signature was measured on.
  int points = 0;
};

/// The signature of a scan from its points' elevation angles (points 2.5 to 120 m away: nearer
/// ones are mostly self-hits, whose elevation depends on their offset from the beam origin).
SensorSignature measure_signature(const PointCloud& scan);

/// The preset sensor whose beam count and field of view are nearest to the signature
/// (nominal: vlp16 16 beams -15..+15 deg, hdl32 32 beams -30.67..+10.67, hdl64 64 beams
/// -24.9..+2, os1-64 64 beams -16.6..+16.6, os-128 128 beams -22.5..+22.5). A distance is
/// |log2(rings / beams)| + (|lowest - low| + |highest - high|) / 5 deg: missing sky returns
/// lower the highest beam seen, and blurred beams lower the count, so neither decides alone.
SensorModel nearest_sensor(const SensorSignature& signature);

/// The preset's value of every preset-managed key (sensor_preset_keys()) that
/// config.explicit_keys does not name is set; config.sensor becomes `model`. kNone and kAuto
/// change nothing.
void apply_sensor_preset(SensorModel model, TrackerConfig& config);

/// The keys (dotted YAML paths) a preset sets.
const std::vector<std::string>& sensor_preset_keys();

/// YAML name of a sensor model ("auto", "none", "hdl64", "hdl32", "vlp16", "os1-64", "os-128").
const char* sensor_name(SensorModel model);
/// The model of a YAML name, or nothing.
std::optional<SensorModel> sensor_from_name(const std::string& name);

}  // namespace litamin2
