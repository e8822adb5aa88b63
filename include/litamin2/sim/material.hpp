#pragma once
/// Surface materials of the simulated world and how a LiDAR sees them.

#include <cstdint>

namespace litamin2::sim {

/// Kind of surface a triangle belongs to.
enum class Material : std::uint8_t {
  kAsphalt,
  kSidewalk,
  kGrass,
  kWall,
  kGlass,
  kConcrete,
  kMetal,
  kSign,
  kFoliage,
  kBark,
  kCarPaint,
  kCarGlass,
  kClothing,
  kCount
};

/// Optical properties used by the ray caster.
struct MaterialProperties {
  /// Typical diffuse reflectivity at 905 nm in [0, 1] (triangles may vary it).
  float reflectivity;
  /// Extra probability that a return from this surface is lost (glass, dark paint).
  float dropout;
};

/// Properties of a material.
MaterialProperties material_properties(Material m);

/// Human-readable name ("asphalt", "wall", ...).
const char* material_name(Material m);

}  // namespace litamin2::sim
