#include "litamin2/sim/material.hpp"

namespace litamin2::sim {

MaterialProperties material_properties(Material m) {
  switch (m) {
    case Material::kAsphalt:
      return {0.12f, 0.01f};
    case Material::kSidewalk:
      return {0.25f, 0.0f};
    case Material::kGrass:
      return {0.45f, 0.02f};
    case Material::kWall:
      return {0.45f, 0.0f};
    case Material::kGlass:
      return {0.15f, 0.6f};
    case Material::kConcrete:
      return {0.35f, 0.0f};
    case Material::kMetal:
      return {0.50f, 0.05f};
    case Material::kSign:
      return {0.95f, 0.0f};
    case Material::kFoliage:
      return {0.50f, 0.10f};
    case Material::kBark:
      return {0.30f, 0.0f};
    case Material::kCarPaint:
      return {0.30f, 0.05f};
    case Material::kCarGlass:
      return {0.10f, 0.5f};
    case Material::kClothing:
      return {0.30f, 0.02f};
    case Material::kCount:
      break;
  }
  return {0.3f, 0.0f};
}

const char* material_name(Material m) {
  switch (m) {
    case Material::kAsphalt:
      return "asphalt";
    case Material::kSidewalk:
      return "sidewalk";
    case Material::kGrass:
      return "grass";
    case Material::kWall:
      return "wall";
    case Material::kGlass:
      return "glass";
    case Material::kConcrete:
      return "concrete";
    case Material::kMetal:
      return "metal";
    case Material::kSign:
      return "sign";
    case Material::kFoliage:
      return "foliage";
    case Material::kBark:
      return "bark";
    case Material::kCarPaint:
      return "car_paint";
    case Material::kCarGlass:
      return "car_glass";
    case Material::kClothing:
      return "clothing";
    case Material::kCount:
      break;
  }
  return "unknown";
}

}  // namespace litamin2::sim
