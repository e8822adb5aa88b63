#include "litamin2/config/tracker_config_yaml.hpp"

#include "litamin2/config/config_file.hpp"
#include "litamin2/config/yaml_section.hpp"

#include <yaml-cpp/yaml.h>

#include <string>
#include <utility>
#include <vector>

namespace litamin2 {

using config::load_config_file;
using config::YamlSection;

namespace {

const std::vector<std::pair<std::string, CostMode>> kModes = {{"icp", CostMode::kIcp},
                                                              {"icp+cov", CostMode::kIcpCov}};
const std::vector<std::pair<std::string, CovHessian>> kCovHessians = {
    {"full", CovHessian::kFull}, {"gauss_newton", CovHessian::kGaussNewton}};
const std::vector<std::pair<std::string, CovEnergy>> kCovEnergies = {
    {"squared", CovEnergy::kSquared}, {"linear", CovEnergy::kLinear}};
const std::vector<std::pair<std::string, CorrespondenceMethod>> kCorrespondences = {
    {"voxel27", CorrespondenceMethod::kVoxel27}, {"kdtree", CorrespondenceMethod::kKdTree}};
const std::vector<std::pair<std::string, TimeSource>> kTimeSources = {
    {"field", TimeSource::kField},
    {"azimuth", TimeSource::kAzimuth},
    {"field_or_azimuth", TimeSource::kFieldOrAzimuth}};
const std::vector<std::pair<std::string, RegularizationMethod>> kRegularizations = {
    {"eigen_clamp", RegularizationMethod::kEigenClamp}, {"plane", RegularizationMethod::kPlane}};

template <class Enum>
std::string enum_name(Enum value, const std::vector<std::pair<std::string, Enum>>& names) {
  for (const auto& [n, v] : names) {
    if (v == value) return n;
  }
  return "?";
}

}  // namespace

TrackerConfig tracker_config_from_yaml(const YAML::Node& node) {
  TrackerConfig config;
  YamlSection root(node, "");

  YamlSection voxelizer(root.child("voxelizer"), "voxelizer");
  VoxelizerConfig& v = config.voxelizer;
  voxelizer.read("voxel_size", v.voxel_size);
  voxelizer.read("min_points", v.min_points);
  voxelizer.read("min_range", v.min_range);
  voxelizer.read("max_range", v.max_range);
  YamlSection regularizer(voxelizer.child("regularization"), "voxelizer.regularization");
  regularizer.read_enum("method", v.regularizer.method, kRegularizations);
  regularizer.read("min_eigen_ratio", v.regularizer.min_eigen_ratio);
  regularizer.read("shape_min_eigen_ratio", v.regularizer.shape_min_eigen_ratio);
  regularizer.read("plane_epsilon", v.regularizer.plane_epsilon);
  regularizer.read("min_eigenvalue", v.regularizer.min_eigenvalue);
  regularizer.reject_unknown();
  voxelizer.reject_unknown();

  YamlSection map(root.child("map"), "map");
  map.read("radius", config.map.radius);
  map.reject_unknown();

  YamlSection registration(root.child("registration"), "registration");
  RegistrationConfig& r = config.registration;
  registration.read_enum("mode", r.mode, kModes);
  registration.read("sigma_icp", r.sigma_icp);
  registration.read("sigma_cov", r.sigma_cov);
  registration.read("cov_min_points", r.cov_min_points);
  registration.read("max_isotropy", r.max_isotropy);
  registration.read("lambda", r.lambda);
  registration.read_enum("cov_energy", r.cov_energy, kCovEnergies);
  registration.read_enum("cov_hessian", r.cov_hessian, kCovHessians);
  registration.read_enum("correspondence", r.correspondence, kCorrespondences);
  registration.read("max_correspondence_distance", r.max_correspondence_distance);
  registration.read("max_iterations", r.max_iterations);
  registration.read("rotation_tolerance", r.rotation_tolerance);
  registration.read("translation_tolerance", r.translation_tolerance);
  registration.read("min_correspondences", r.min_correspondences);
  registration.read("block_size", r.block_size);
  registration.read("regrid_translation", r.regrid_translation);
  registration.read("regrid_rotation_deg", r.regrid_rotation_deg);
  registration.read("max_regrids", r.max_regrids);
  registration.reject_unknown();

  YamlSection keyframe(root.child("keyframe"), "keyframe");
  keyframe.read("distance", config.keyframe.distance);
  keyframe.read("angle_deg", config.keyframe.angle_deg);
  keyframe.reject_unknown();

  YamlSection deskew(root.child("deskew"), "deskew");
  DeskewConfig& d = config.deskew;
  deskew.read("enabled", d.enabled);
  deskew.read_enum("time_source", d.time_source, kTimeSources);
  deskew.read("passes", d.passes);
  YamlSection azimuth(deskew.child("azimuth"), "deskew.azimuth");
  azimuth.read("period_s", d.azimuth.period_s);
  azimuth.read("start_deg", d.azimuth.start_deg);
  azimuth.read("clockwise", d.azimuth.clockwise);
  azimuth.reject_unknown();
  deskew.reject_unknown();

  root.reject_unknown();
  validate(config);
  return config;
}

TrackerConfig load_tracker_config(const std::string& path) {
  return load_config_file(path, [](const YAML::Node& node) {
    return tracker_config_from_yaml(node.IsMap() && node["tracker"] ? node["tracker"] : node);
  });
}

std::string tracker_config_to_yaml(const TrackerConfig& c) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "voxelizer" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "voxel_size" << YAML::Value << c.voxelizer.voxel_size;
  out << YAML::Key << "min_points" << YAML::Value << c.voxelizer.min_points;
  out << YAML::Key << "min_range" << YAML::Value << c.voxelizer.min_range;
  out << YAML::Key << "max_range" << YAML::Value << c.voxelizer.max_range;
  out << YAML::Key << "regularization" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "method" << YAML::Value
      << enum_name(c.voxelizer.regularizer.method, kRegularizations);
  out << YAML::Key << "min_eigen_ratio" << YAML::Value << c.voxelizer.regularizer.min_eigen_ratio;
  out << YAML::Key << "shape_min_eigen_ratio" << YAML::Value
      << c.voxelizer.regularizer.shape_min_eigen_ratio;
  out << YAML::Key << "plane_epsilon" << YAML::Value << c.voxelizer.regularizer.plane_epsilon;
  out << YAML::Key << "min_eigenvalue" << YAML::Value << c.voxelizer.regularizer.min_eigenvalue;
  out << YAML::EndMap << YAML::EndMap;
  out << YAML::Key << "map" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "radius" << YAML::Value << c.map.radius << YAML::EndMap;
  const RegistrationConfig& r = c.registration;
  out << YAML::Key << "registration" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "mode" << YAML::Value << enum_name(r.mode, kModes);
  out << YAML::Key << "sigma_icp" << YAML::Value << r.sigma_icp;
  out << YAML::Key << "sigma_cov" << YAML::Value << r.sigma_cov;
  out << YAML::Key << "cov_min_points" << YAML::Value << r.cov_min_points;
  out << YAML::Key << "max_isotropy" << YAML::Value << r.max_isotropy;
  out << YAML::Key << "lambda" << YAML::Value << r.lambda;
  out << YAML::Key << "cov_energy" << YAML::Value << enum_name(r.cov_energy, kCovEnergies);
  out << YAML::Key << "cov_hessian" << YAML::Value << enum_name(r.cov_hessian, kCovHessians);
  out << YAML::Key << "correspondence" << YAML::Value
      << enum_name(r.correspondence, kCorrespondences);
  out << YAML::Key << "max_correspondence_distance" << YAML::Value << r.max_correspondence_distance;
  out << YAML::Key << "max_iterations" << YAML::Value << r.max_iterations;
  out << YAML::Key << "rotation_tolerance" << YAML::Value << r.rotation_tolerance;
  out << YAML::Key << "translation_tolerance" << YAML::Value << r.translation_tolerance;
  out << YAML::Key << "min_correspondences" << YAML::Value << r.min_correspondences;
  out << YAML::Key << "block_size" << YAML::Value << r.block_size;
  out << YAML::Key << "regrid_translation" << YAML::Value << r.regrid_translation;
  out << YAML::Key << "regrid_rotation_deg" << YAML::Value << r.regrid_rotation_deg;
  out << YAML::Key << "max_regrids" << YAML::Value << r.max_regrids;
  out << YAML::EndMap;
  out << YAML::Key << "keyframe" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "distance" << YAML::Value << c.keyframe.distance;
  out << YAML::Key << "angle_deg" << YAML::Value << c.keyframe.angle_deg;
  out << YAML::EndMap;
  const DeskewConfig& d = c.deskew;
  out << YAML::Key << "deskew" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << d.enabled;
  out << YAML::Key << "time_source" << YAML::Value << enum_name(d.time_source, kTimeSources);
  out << YAML::Key << "passes" << YAML::Value << d.passes;
  out << YAML::Key << "azimuth" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "period_s" << YAML::Value << d.azimuth.period_s;
  out << YAML::Key << "start_deg" << YAML::Value << d.azimuth.start_deg;
  out << YAML::Key << "clockwise" << YAML::Value << d.azimuth.clockwise;
  out << YAML::EndMap << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace litamin2
