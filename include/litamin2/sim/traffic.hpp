#pragma once
/// Moving vehicles and pedestrians: actors that follow the ego trajectory's road with their own
/// speeds, so their pose changes between sweeps and within one. A lead car keeps a varying gap
/// ahead of the ego vehicle in its lane, oncoming cars pass in the next lane, pedestrians walk
/// along the sidewalks. Deterministic in (ego path, world, seed, options).

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "litamin2/sim/triangle_mesh.hpp"
#include "litamin2/sim/world.hpp"

namespace litamin2::sim {

/// Kind of a moving actor.
enum class ActorKind : std::uint8_t {
  kLeadVehicle,      ///< Car ahead in the ego lane, gap varying slowly.
  kOncomingVehicle,  ///< Car driving the other way in the lane to the left.
  kPedestrian,       ///< Person walking along a sidewalk (not on open highway stretches).
};

/// How much traffic there is.
struct TrafficOptions {
  /// One car ahead of the ego vehicle in its lane.
  bool lead_vehicle = false;
  /// Oncoming cars per km of road (on average, over the whole drive).
  double oncoming_per_km = 0.0;
  /// Pedestrians per km of road (in built-up and green districts).
  double pedestrians_per_km = 0.0;
  /// Lateral offset of the oncoming lane to the left of the ego path, metres.
  double oncoming_lane_offset = 2.8;

  /// True if any actor is requested.
  bool any() const { return lead_vehicle || oncoming_per_km > 0 || pedestrians_per_km > 0; }
  /// Throws std::invalid_argument for negative or non-finite densities (at most 200 per km) or
  /// a lane offset outside [1.5, 10] m.
  void validate() const;
};

/// The actors of one drive and their motion.
class Traffic {
 public:
  /// Actors along `ego_path` (vehicle poses in the world frame, one every `period` seconds
  /// from time 0). The world gives the ground height and the districts and must outlive the
  /// Traffic. Throws
  /// std::invalid_argument for invalid options, an empty path or a period <= 0.
  Traffic(const std::vector<Eigen::Isometry3d>& ego_path, double period, const World& world,
          std::uint64_t seed, const TrafficOptions& options);

  /// Number of actors.
  std::size_t size() const { return actors_.size(); }
  /// Kind of actor i.
  ActorKind kind(std::size_t i) const { return actors_[i].kind; }
  /// Mesh of actor i in its own frame (x forward, z up, origin on the ground at its centre).
  const TriangleMesh& mesh(std::size_t i) const { return meshes_[i]; }
  /// World pose of actor i's frame at time t (seconds on the ego path's clock).
  Eigen::Isometry3d pose(std::size_t i, double t) const;
  /// Actors whose centre is within `radius` of `position` (horizontally) at time t.
  std::vector<std::size_t> near(const Eigen::Vector3d& position, double radius, double t) const;
  /// Arc length of the ego vehicle along its path at time t, metres.
  double ego_arc(double t) const;

 private:
  struct Actor {
    ActorKind kind = ActorKind::kLeadVehicle;
    double arc0 = 0.0;       ///< arc length at time 0 (lead: mean gap)
    double speed = 0.0;      ///< signed speed along the path, m/s (lead: gap amplitude)
    double lateral = 0.0;    ///< offset to the left of the path, metres
    double phase = 0.0;      ///< lead: phase of the gap oscillation
    double period = 1.0;     ///< lead: period of the gap oscillation, s
    bool backwards = false;  ///< faces against the path direction
  };
  /// Position (x, y) and unit heading of the path at arc length s (extrapolated at the ends).
  void at_arc(double s, Eigen::Vector2d& pos, Eigen::Vector2d& tan) const;
  /// Arc length of actor i at time t.
  double actor_arc(const Actor& a, double t) const;

  const World& world_;
  /// Ego path positions (x, y) with distinct neighbours, their arc lengths.
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> arcs_;
  /// Ego arc length at each frame.
  std::vector<double> frame_arcs_;
  double period_;
  std::vector<Actor> actors_;
  std::vector<TriangleMesh> meshes_;
};

}  // namespace litamin2::sim
