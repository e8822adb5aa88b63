#include "litamin2/sim/ground.hpp"

#include <algorithm>
#include <cmath>

#include "litamin2/sim/random.hpp"

namespace litamin2::sim {
namespace {

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

Ground::Ground(const RoadNetwork& roads, const WorldOptions& options, std::uint64_t seed)
    : roads_(roads), opt_(options), seed_(seed) {}

double Ground::height(double x, double y) const {
  const auto [d, i] = roads_.nearest(x, y, 200.0);
  const District district = i >= 0 ? roads_.sample(i).district : District::kUrban;
  return height(x, y, roads_.road_height(x, y), d, district);
}

double Ground::height(double x, double y, District district) const {
  const auto [d, i] = roads_.nearest(x, y, 200.0);
  (void)i;
  return height(x, y, roads_.road_height(x, y), d, district);
}

double Ground::height(double x, double y, double base, double d, District district) const {
  double z = base;
  const bool open = district == District::kOpen;
  const double road = open ? opt_.road_half_width + 3.0 : opt_.road_half_width;
  // Terrain: hills and embankments away from the road.
  const double amp = opt_.terrain_amplitude * (open ? 1.6 : 1.0);
  if (amp > 0) {
    const double t =
        0.6 * value_noise(x / 23.0, y / 23.0, 11) + value_noise(x / 71.0, y / 71.0, 12);
    z += amp * t * smoothstep(road + 3.0, road + 30.0, d);
  }
  // Gentle undulation everywhere, small on the road.
  if (opt_.ground_roughness > 0) {
    z += 2.5 * opt_.ground_roughness * value_noise(x / 7.0, y / 7.0, 13) * (d < road ? 0.5 : 1.0);
  }
  if (!open && district != District::kGreen) {
    z += opt_.kerb_height * smoothstep(road, road + 0.25, d);
  }
  // Short bumps: patches, ruts and lumpy verges (twice as strong off the road).
  if (opt_.ground_bump_amplitude > 0) {
    const double bumps =
        0.6 * value_noise(x / 3.5, y / 3.5, 14) + 0.4 * value_noise(x / 1.6, y / 1.6, 15);
    z += opt_.ground_bump_amplitude * bumps * (d < road ? 1.0 : 2.0);
  }
  return z;
}

double Ground::value_noise(double x, double y, std::uint64_t salt) const {
  const double fx = std::floor(x), fy = std::floor(y);
  const double tx = smoothstep(0, 1, x - fx), ty = smoothstep(0, 1, y - fy);
  auto at = [&](double ix, double iy) {
    const std::uint64_t h =
        hash_combine(hash_combine(hash_combine(seed_, salt),
                                  static_cast<std::uint64_t>(static_cast<std::int64_t>(ix))),
                     static_cast<std::uint64_t>(static_cast<std::int64_t>(iy)));
    return static_cast<double>(h >> 11) * 0x1.0p-52 - 1.0;
  };
  return (1 - ty) * ((1 - tx) * at(fx, fy) + tx * at(fx + 1, fy)) +
         ty * ((1 - tx) * at(fx, fy + 1) + tx * at(fx + 1, fy + 1));
}

}  // namespace litamin2::sim
