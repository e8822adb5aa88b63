#include "litamin2/sim/lidar_model.hpp"

namespace litamin2::sim {

LidarModel LidarModel::hdl64() {
  LidarModel m;
  m.name = "hdl64";
  // Upper block: 32 lasers +2.0 .. -8.33 deg; lower block: 32 lasers -8.83 .. -24.9 deg.
  for (int i = 0; i < 32; ++i) m.elevations_deg.push_back(2.0 - i * (10.33 / 31.0));
  for (int i = 0; i < 32; ++i) m.elevations_deg.push_back(-8.83 - i * ((24.9 - 8.83) / 31.0));
  m.azimuth_steps = 2048;
  m.max_range = 120.0;
  return m;
}

LidarModel LidarModel::vlp16() {
  LidarModel m;
  m.name = "vlp16";
  for (int i = 0; i < 16; ++i) m.elevations_deg.push_back(15.0 - 2.0 * i);
  m.azimuth_steps = 1800;
  m.min_range = 1.0;
  m.max_range = 100.0;
  m.reference_range = 250.0;
  m.range_noise_sigma = 0.03;
  return m;
}

LidarModel LidarModel::os128() {
  LidarModel m;
  m.name = "os128";
  for (int i = 0; i < 128; ++i) m.elevations_deg.push_back(22.5 - i * (45.0 / 127.0));
  m.azimuth_steps = 2048;
  m.min_range = 1.0;
  m.max_range = 120.0;
  m.reference_range = 300.0;
  m.range_noise_sigma = 0.02;
  return m;
}

std::optional<LidarModel> LidarModel::from_name(const std::string& name) {
  if (name == "hdl64") return hdl64();
  if (name == "vlp16") return vlp16();
  if (name == "os128") return os128();
  return std::nullopt;
}

std::vector<std::string> LidarModel::preset_names() {
  return {"hdl64", "vlp16", "os128"};
}

}  // namespace litamin2::sim
