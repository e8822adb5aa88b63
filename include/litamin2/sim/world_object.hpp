#pragma once
/// Descriptors of the objects placed in the simulated world and the generator of their meshes.

#include <Eigen/Core>
#include <cstdint>

#include "litamin2/sim/triangle_mesh.hpp"

namespace litamin2::sim {

/// Kind of a placed object.
enum class ObjectKind : std::uint8_t {
  kBuilding,   ///< Block with a relief facade (windows, balconies, cornices) towards the road.
  kHouse,      ///< Small house with a pitched roof.
  kTree,       ///< Trunk, branches and a crown of irregular small triangles.
  kBush,       ///< Irregular blob of small triangles on the ground.
  kHedge,      ///< Elongated bush clutter along the road.
  kPole,       ///< Street lamp: pole with an arm and a head.
  kSign,       ///< Thin post with a retro-reflective plate.
  kCar,        ///< Parked car (body, tapered cabin with glass, wheels).
  kGuardRail,  ///< Highway guard rail segment with posts.
  kWall,       ///< Low garden or noise wall with an irregular top.
};

/// Character of a stretch of road.
enum class District : std::uint8_t {
  kUrban,     ///< Continuous facades, parked cars, street trees and lamps.
  kSuburban,  ///< Houses with gaps, hedges, bushes, trees, some parked cars.
  kGreen,     ///< Trees and bushes, few structures.
  kOpen,      ///< Highway: guard rails, rare signs and trees, open terrain.
};

/// One placed object. Local frame: x along the road, y away from the road (the front faces
/// -y), z up; the origin is on the ground at the footprint centre.
struct WorldObject {
  ObjectKind kind = ObjectKind::kBuilding;
  /// Footprint centre in the world frame.
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  /// Rotation about z of the local frame, radians.
  double yaw = 0.0;
  /// Ground height at the centre.
  double ground_z = 0.0;
  /// Size: length along x, depth along y, height (metres).
  Eigen::Vector3d size = Eigen::Vector3d::Ones();
  /// Seed of the object's own details.
  std::uint64_t seed = 0;
};

/// Appends the triangles of an object to a mesh (deterministic from the descriptor).
void build_object_mesh(const WorldObject& object, TriangleMesh& mesh);

/// Name of an object kind ("building", "tree", ...).
const char* object_kind_name(ObjectKind kind);

}  // namespace litamin2::sim
