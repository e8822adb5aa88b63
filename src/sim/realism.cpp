#include "litamin2/sim/realism.hpp"

#include <algorithm>
#include <stdexcept>

namespace litamin2::sim {

void apply_realism(const std::string& name, RealismSettings& s) {
  if (name == "none") return;
  if (name != "street") {
    throw std::invalid_argument("unknown realism preset '" + name + "' (none, street)");
  }
  // The real VLP-16 drive's ranges are smoother than the preset's 3 cm (robust 0.8 cm along a
  // ground ring, 1 cm rounding included); its roughness comes from the surfaces instead.
  if (s.model.name == "vlp16") s.model.range_noise_sigma = 0.01;
  // Returns from 1 m on (the HDL-64 preset's 2.5 m would hide the self-hits).
  s.model.min_range = std::min(s.model.min_range, 1.0);
  // Sweep as Velodyne drivers cut it: starting behind the car, turning clockwise, with the
  // vehicle moving during the 100 ms.
  s.rig.sweep.motion = true;
  s.rig.sweep.start_azimuth_deg = 180.0;
  s.rig.sweep.clockwise = true;
  s.rig.mount.roll_deg = 1.0;
  s.rig.mount.pitch_deg = 0.0;
  s.rig.body = EgoBody::roof_rack();
  // Ground and vegetation that are not planes.
  s.world.ground_bump_amplitude = 0.05;
  s.world.grass_height = 0.12;
  s.world.foliage_penetration = 0.25;
  s.world.kerb_height = 0.15;
  // Greener and more cluttered than the default mix, as the real drive's scans are (a third of
  // its 3 m voxels are round, not planar: trees, bushes, cars).
  s.world.district_weights = {0.2, 0.4, 0.4};
  s.world.density *= 2.0;
  // Traffic.
  s.traffic.lead_vehicle = true;
  s.traffic.oncoming_per_km = 8.0;
  s.traffic.pedestrians_per_km = 30.0;
  // A recording that loses frames.
  s.drops.probability = 0.5;
  s.drops.max_gap = 3;
}

std::vector<std::string> realism_names() {
  return {"none", "street"};
}

}  // namespace litamin2::sim
