#include "litamin2/sim/traffic.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "litamin2/sim/random.hpp"
#include "litamin2/sim/world_object.hpp"

namespace litamin2::sim {
namespace {

/// A person of height h in its own frame: two legs, torso, arms and head.
TriangleMesh pedestrian_mesh(Rng& rng) {
  TriangleMesh mesh;
  const float h = static_cast<float>(rng.uniform(1.55, 1.9));
  const float refl = static_cast<float>(rng.uniform(0.1, 0.5));
  const float leg = 0.48f * h, torso = 0.32f * h;
  auto box = [&](float x, float y, float z, float sx, float sy, float sz) {
    Eigen::Isometry3f p = Eigen::Isometry3f::Identity();
    p.translation() = Eigen::Vector3f(x, y, z);
    mesh.add_box(p, Eigen::Vector3f(sx, sy, sz), Material::kClothing, refl);
  };
  box(0.0f, -0.1f, 0.5f * leg, 0.14f, 0.14f, leg);                   // legs
  box(0.0f, 0.1f, 0.5f * leg, 0.14f, 0.14f, leg);                    //
  box(0.0f, 0.0f, leg + 0.5f * torso, 0.24f, 0.42f, torso);          // torso
  box(0.0f, -0.27f, leg + 0.45f * torso, 0.1f, 0.1f, 0.8f * torso);  // arms
  box(0.0f, 0.27f, leg + 0.45f * torso, 0.1f, 0.1f, 0.8f * torso);
  box(0.0f, 0.0f, h - 0.11f, 0.19f, 0.17f, 0.22f);  // head
  return mesh;
}

/// A car of random size in its own frame (the parked-car model).
TriangleMesh car_mesh(Rng& rng) {
  WorldObject o;
  o.kind = ObjectKind::kCar;
  o.size = Eigen::Vector3d(rng.uniform(3.9, 4.9), rng.uniform(1.7, 1.95), rng.uniform(1.4, 1.65));
  o.seed = rng.next();
  TriangleMesh mesh;
  build_object_mesh(o, mesh);
  return mesh;
}

}  // namespace

void TrafficOptions::validate() const {
  auto density = [](double v, const char* name) {
    if (!std::isfinite(v) || v < 0.0 || v > 200.0) {
      throw std::invalid_argument(std::string("traffic: ") + name + " " + std::to_string(v) +
                                  " per km must be in [0, 200]");
    }
  };
  density(oncoming_per_km, "oncoming vehicles");
  density(pedestrians_per_km, "pedestrians");
  if (!(oncoming_lane_offset >= 1.5 && oncoming_lane_offset <= 10.0)) {
    throw std::invalid_argument("traffic: oncoming lane offset " +
                                std::to_string(oncoming_lane_offset) + " m must be in [1.5, 10]");
  }
}

Traffic::Traffic(const std::vector<Eigen::Isometry3d>& ego_path, double period, const World& world,
                 std::uint64_t seed, const TrafficOptions& options)
    : world_(world), period_(period) {
  options.validate();
  if (ego_path.empty()) throw std::invalid_argument("Traffic: empty ego path");
  if (!(period > 0.0)) throw std::invalid_argument("Traffic: period must be positive");
  // Arc length of the path; points closer than 0.5 m to the previous kept one are skipped so
  // the heading is defined.
  double arc = 0.0;
  for (const auto& T : ego_path) {
    const Eigen::Vector2d p = T.translation().head<2>();
    if (!points_.empty()) arc += (p - points_.back()).norm();
    if (points_.empty() || (p - points_.back()).norm() >= 0.5) {
      points_.push_back(p);
      arcs_.push_back(arc);
    }
    frame_arcs_.push_back(arc);
  }
  if (points_.size() == 1) {  // a standing vehicle: give the path a heading
    const Eigen::Vector2d x = ego_path.front().linear().col(0).head<2>().normalized();
    points_.push_back(points_.front() + x);
    arcs_.push_back(1.0);
  }
  const double length = arcs_.back();
  const double duration = static_cast<double>(ego_path.size() - 1) * period;
  const double ego_speed = duration > 0 ? length / duration : 0.0;

  Rng rng(hash_combine(seed, 0x7aff1c));
  if (options.lead_vehicle) {
    Actor a;
    a.kind = ActorKind::kLeadVehicle;
    a.arc0 = rng.uniform(12.0, 22.0) + 0.8 * ego_speed;  // mean gap
    a.speed = rng.uniform(3.0, 6.0);                     // gap amplitude
    a.period = rng.uniform(20.0, 40.0);
    a.phase = rng.uniform(0.0, 2.0 * M_PI);
    actors_.push_back(a);
    meshes_.push_back(car_mesh(rng));
  }
  if (options.oncoming_per_km > 0) {
    // Spread over the stretch the oncoming cars cover during the drive, so the density stays
    // the same from the first frame to the last.
    const double speed = std::max(8.0, ego_speed);
    const double span = length + 1.3 * speed * duration + 200.0;
    const auto n = static_cast<std::size_t>(std::llround(options.oncoming_per_km * span / 1000.0));
    for (std::size_t k = 0; k < n; ++k) {
      Actor a;
      a.kind = ActorKind::kOncomingVehicle;
      a.arc0 = rng.uniform(-100.0, span - 100.0);
      a.speed = -speed * rng.uniform(0.8, 1.3);
      a.lateral = options.oncoming_lane_offset + rng.uniform(-0.3, 0.3);
      a.backwards = true;
      actors_.push_back(a);
      meshes_.push_back(car_mesh(rng));
    }
  }
  if (options.pedestrians_per_km > 0) {
    const auto n =
        static_cast<std::size_t>(std::llround(options.pedestrians_per_km * length / 1000.0));
    const double kerb = world.options().road_half_width;
    for (std::size_t k = 0; k < n; ++k) {
      Actor a;
      a.kind = ActorKind::kPedestrian;
      a.arc0 = rng.uniform(0.0, length);
      const double side = rng.chance(0.5) ? 1.0 : -1.0;
      a.lateral = side * (kerb + rng.uniform(0.8, 2.5));
      a.backwards = rng.chance(0.5);
      a.speed = (a.backwards ? -1.0 : 1.0) * rng.uniform(0.8, 1.6);
      Rng mesh_rng(rng.next());
      Eigen::Vector2d pos, tan;
      at_arc(a.arc0, pos, tan);
      const Eigen::Vector2d at = pos + a.lateral * Eigen::Vector2d(-tan.y(), tan.x());
      if (world.district_at(at.x(), at.y()) == District::kOpen) continue;
      actors_.push_back(a);
      meshes_.push_back(pedestrian_mesh(mesh_rng));
    }
  }
}

double Traffic::ego_arc(double t) const {
  const double f = t / period_;
  if (f <= 0.0) return frame_arcs_.front();
  const auto i = static_cast<std::size_t>(std::floor(f));
  if (i + 1 >= frame_arcs_.size()) return frame_arcs_.back();
  const double s = f - static_cast<double>(i);
  return frame_arcs_[i] + s * (frame_arcs_[i + 1] - frame_arcs_[i]);
}

double Traffic::actor_arc(const Actor& a, double t) const {
  if (a.kind == ActorKind::kLeadVehicle) {
    return ego_arc(t) + a.arc0 + a.speed * std::sin(2.0 * M_PI * t / a.period + a.phase);
  }
  return a.arc0 + a.speed * t;
}

void Traffic::at_arc(double s, Eigen::Vector2d& pos, Eigen::Vector2d& tan) const {
  const std::size_t n = points_.size();
  const auto it = std::upper_bound(arcs_.begin(), arcs_.end(), s);
  std::size_t i = it == arcs_.begin() ? 0 : static_cast<std::size_t>(it - arcs_.begin()) - 1;
  i = std::min(i, n - 2);
  const Eigen::Vector2d d = points_[i + 1] - points_[i];
  // Heading blended over the neighbouring segments so the actor turns smoothly.
  const double u = (s - arcs_[i]) / (arcs_[i + 1] - arcs_[i]);
  pos = points_[i] + u * d;
  Eigen::Vector2d t0 = i > 0 ? Eigen::Vector2d(points_[i + 1] - points_[i - 1]) : d;
  Eigen::Vector2d t1 = i + 2 < n ? Eigen::Vector2d(points_[i + 2] - points_[i]) : d;
  const double w = std::clamp(u, 0.0, 1.0);
  tan = ((1.0 - w) * t0.normalized() + w * t1.normalized()).normalized();
  if (!tan.allFinite()) tan = d.normalized();
}

Eigen::Isometry3d Traffic::pose(std::size_t i, double t) const {
  const Actor& a = actors_[i];
  Eigen::Vector2d pos, tan;
  at_arc(actor_arc(a, t), pos, tan);
  const Eigen::Vector2d xy = pos + a.lateral * Eigen::Vector2d(-tan.y(), tan.x());
  const double yaw = std::atan2(tan.y(), tan.x()) + (a.backwards ? M_PI : 0.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(xy.x(), xy.y(), world_.ground_height(xy.x(), xy.y()));
  return T;
}

std::vector<std::size_t> Traffic::near(const Eigen::Vector3d& position, double radius,
                                       double t) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < actors_.size(); ++i) {
    Eigen::Vector2d pos, tan;
    at_arc(actor_arc(actors_[i], t), pos, tan);
    const Eigen::Vector2d xy = pos + actors_[i].lateral * Eigen::Vector2d(-tan.y(), tan.x());
    if ((xy - position.head<2>()).norm() <= radius) out.push_back(i);
  }
  return out;
}

}  // namespace litamin2::sim
