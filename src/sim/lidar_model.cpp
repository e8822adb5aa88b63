#include "litamin2/sim/lidar_model.hpp"

#include <cmath>
#include <stdexcept>

namespace litamin2::sim {

void LidarModel::validate() const {
  const std::string who = "sensor model '" + name + "': ";
  if (elevations_deg.empty()) throw std::invalid_argument(who + "no beams");
  for (double e : elevations_deg) {
    if (!std::isfinite(e) || std::abs(e) > 90.0) {
      throw std::invalid_argument(who + "beam elevation " + std::to_string(e) +
                                  " deg outside [-90, 90]");
    }
  }
  if (azimuth_steps < 8) throw std::invalid_argument(who + "needs at least 8 azimuth steps");
  if (!(min_range >= 0.0 && min_range < max_range && std::isfinite(max_range))) {
    throw std::invalid_argument(who + "needs 0 <= min_range < max_range");
  }
  if (!(range_noise_sigma >= 0.0 && range_noise_sigma < 5.0)) {
    throw std::invalid_argument(who + "range noise must be in [0, 5) m");
  }
  if (!(dropout >= 0.0 && dropout <= 1.0)) {
    throw std::invalid_argument(who + "dropout must be in [0, 1]");
  }
  if (!(mount_height > 0.0 && std::isfinite(mount_height))) {
    throw std::invalid_argument(who + "mount height must be positive");
  }
}

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
