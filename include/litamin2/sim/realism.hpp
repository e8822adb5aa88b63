#pragma once
/// Realism presets: one name that sets what makes real drives harder than the procedural
/// default (motion within the sweep, self-hits, mount tilt, rough ground and porous, denser
/// vegetation, moving actors, dropped frames). "none" leaves every setting as it is, so
/// the default simulation stays byte-identical; single options can override a preset.

#include <string>
#include <vector>

#include "litamin2/sim/frame_selection.hpp"
#include "litamin2/sim/lidar_model.hpp"
#include "litamin2/sim/sensor_rig.hpp"
#include "litamin2/sim/traffic.hpp"
#include "litamin2/sim/world.hpp"

namespace litamin2::sim {

/// Every setting a preset may change.
struct RealismSettings {
  /// Sensor (range noise).
  LidarModel model;
  /// Sweep timing and motion, mount tilt, ego body.
  SensorRig rig;
  /// Ground and vegetation.
  WorldOptions world;
  /// Moving actors.
  TrafficOptions traffic;
  /// Dropped frames.
  FrameDropOptions drops;
};

/// Applies preset `name` to `settings` (its model is the sensor chosen; some values depend on
/// it). "none": no change. "street": the real VLP-16 drive's traits (see docs/simulator.md):
/// sweep motion starting behind the car and turning clockwise, the roof-rack body, mount roll
/// 1 deg, returns from 1 m, range noise 1 cm for the VLP-16 (as measured on that drive), short
/// ground bumps (5 cm), grass 12 cm high, foliage penetration 0.25 m, a 15 cm kerb, greener
/// districts (urban 0.2, suburban 0.4, green 0.4) with twice the object density, a lead car,
/// 8 oncoming cars and 30 pedestrians per km, half the frames dropped (runs of up to 3).
/// Throws std::invalid_argument for an unknown name.
void apply_realism(const std::string& name, RealismSettings& settings);

/// Names accepted by apply_realism.
std::vector<std::string> realism_names();

}  // namespace litamin2::sim
