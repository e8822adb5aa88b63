#include "litamin2/sim/ego_body.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace litamin2::sim {

std::optional<BodyHit> EgoBody::intersect(const Eigen::Vector3d& direction) const {
  std::optional<BodyHit> best;
  for (const BodyBox& box : boxes) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    int entry_axis = -1;
    bool miss = false;
    for (int i = 0; i < 3 && !miss; ++i) {
      const double d = direction[i];
      if (std::abs(d) < 1e-12) {
        miss = 0.0 < box.min[i] || 0.0 > box.max[i];
        continue;
      }
      double ta = box.min[i] / d, tb = box.max[i] / d;
      if (ta > tb) std::swap(ta, tb);
      if (ta > t0) {
        t0 = ta;
        entry_axis = i;
      }
      t1 = std::min(t1, tb);
      miss = t0 > t1;
    }
    if (miss || entry_axis < 0 || (best && best->range <= t0)) continue;
    BodyHit hit;
    hit.range = t0;
    hit.normal = Eigen::Vector3d::Zero();
    hit.normal[entry_axis] = direction[entry_axis] > 0 ? -1.0 : 1.0;
    hit.reflectivity = box.reflectivity;
    best = hit;
  }
  return best;
}

void EgoBody::validate() const {
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    const BodyBox& b = boxes[k];
    const std::string name = "ego body box " + std::to_string(k);
    if (!b.min.allFinite() || !b.max.allFinite()) {
      throw std::invalid_argument(name + ": corners must be finite");
    }
    if ((b.min.array() >= b.max.array()).any()) {
      throw std::invalid_argument(name + ": min must be below max on every axis");
    }
    if ((b.min.array() <= 0.0).all() && (b.max.array() >= 0.0).all()) {
      throw std::invalid_argument(name + ": contains the sensor origin");
    }
    if (!(b.reflectivity >= 0.0f && b.reflectivity <= 1.0f)) {
      throw std::invalid_argument(name + ": reflectivity must be in [0, 1]");
    }
    if (b.min.cwiseAbs().maxCoeff() > 10.0 || b.max.cwiseAbs().maxCoeff() > 10.0) {
      throw std::invalid_argument(name + ": farther than 10 m from the sensor");
    }
  }
}

EgoBody EgoBody::none() {
  return {};
}

EgoBody EgoBody::roof_rack() {
  // Fitted to the self-hits of ../shared/data/vlp16_drive (rings -15, -13, -11, -7 deg hit
  // faces at x = -1.13, -1.40, -1.06 and -1.59 m; side rails close the rack at y = +0.6 and
  // -0.73 m; the rack is off-centre to the right as on that car).
  EgoBody b;
  auto box = [&](double x0, double y0, double z0, double x1, double y1, double z1, float refl) {
    b.boxes.push_back({Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1), refl});
  };
  box(-1.25, -0.60, -0.36, -1.13, 0.48, -0.28, 0.25f);   // rear roof edge, seen by -15 deg
  box(-1.55, -0.62, -0.37, -1.40, 0.48, -0.29, 0.25f);   // roof behind it, seen by -13 deg
  box(-1.12, -0.72, -0.235, -1.06, 0.59, -0.185, 0.4f);  // front roof bar, -11 deg
  box(-1.65, -0.72, -0.22, -1.59, 0.59, -0.17, 0.4f);    // rear roof bar, -7 deg
  box(-1.59, 0.55, -0.22, -1.06, 0.61, -0.17, 0.4f);     // left rail
  box(-1.59, -0.76, -0.22, -1.06, -0.70, -0.17, 0.4f);   // right rail
  return b;
}

std::optional<EgoBody> EgoBody::from_name(const std::string& name) {
  if (name == "none") return none();
  if (name == "roof-rack") return roof_rack();
  return std::nullopt;
}

std::vector<std::string> EgoBody::preset_names() {
  return {"none", "roof-rack"};
}

}  // namespace litamin2::sim
