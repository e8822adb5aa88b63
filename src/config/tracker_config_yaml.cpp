#include "litamin2/config/tracker_config_yaml.hpp"

#include "litamin2/config/config_file.hpp"
#include "litamin2/config/yaml_section.hpp"
#include "litamin2/core/sensor_preset.hpp"

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
const std::vector<std::pair<std::string, EgoFilterMode>> kEgoModes = {
    {"off", EgoFilterMode::kOff}, {"box", EgoFilterMode::kBox}, {"auto", EgoFilterMode::kAuto}};

std::vector<std::pair<std::string, SensorModel>> sensor_names() {
  std::vector<std::pair<std::string, SensorModel>> out;
  for (SensorModel m :
       {SensorModel::kAuto, SensorModel::kNone, SensorModel::kHdl64, SensorModel::kHdl32,
        SensorModel::kVlp16, SensorModel::kOs1_64, SensorModel::kOs128})
    out.emplace_back(sensor_name(m), m);
  return out;
}

/// filter.ego_box: [xmin, ymin, zmin, xmax, ymax, zmax] (sensor frame, metres).
void read_box(YamlSection& section, ScanFilterConfig& filter) {
  const YAML::Node node = section.child("ego_box");
  if (!node || node.IsNull()) return;
  const std::string key = section.name("ego_box");
  if (!node.IsSequence() || node.size() != 6)
    throw ConfigError(key + ": expected [xmin, ymin, zmin, xmax, ymax, zmax], got '" +
                      config::yaml_text(node) + "'");
  double v[6];
  for (std::size_t i = 0; i < 6; ++i) {
    try {
      v[i] = node[i].as<double>();
    } catch (const YAML::Exception&) {
      throw ConfigError(key + "[" + std::to_string(i) + "]: cannot read '" +
                        config::yaml_text(node[i]) + "' as a number");
    }
  }
  filter.ego_box_min = Eigen::Vector3d(v[0], v[1], v[2]);
  filter.ego_box_max = Eigen::Vector3d(v[3], v[4], v[5]);
}

template <class Enum>
std::string enum_name(Enum value, const std::vector<std::pair<std::string, Enum>>& names) {
  for (const auto& [n, v] : names) {
    if (v == value) return n;
  }
  return "?";
}

/// A list of numbers (may be empty) under `name`: recovery.motion_scales, first_speeds.
void read_numbers(YamlSection& section, const char* name, std::vector<double>& scales) {
  const YAML::Node node = section.child(name);
  if (!node || node.IsNull()) return;
  const std::string key = section.name(name);
  if (!node.IsSequence())
    throw ConfigError(key + ": expected a list of numbers, got '" + config::yaml_text(node) + "'");
  scales.clear();
  for (std::size_t i = 0; i < node.size(); ++i) {
    try {
      scales.push_back(node[i].as<double>());
    } catch (const YAML::Exception&) {
      throw ConfigError(key + "[" + std::to_string(i) + "]: cannot read '" +
                        config::yaml_text(node[i]) + "' as a number");
    }
  }
}

}  // namespace

TrackerConfig tracker_config_from_yaml(const YAML::Node& node) {
  return tracker_config_from_yaml(node, TrackerConfig{});
}

TrackerConfig tracker_config_from_yaml(const YAML::Node& node, const TrackerConfig& base) {
  TrackerConfig config = base;
  YamlSection root(node, "");
  // Keys a sensor preset manages are recorded when given, so the preset leaves them alone.
  auto read_managed = [&config](YamlSection& section, const char* key, auto& field) {
    if (section.read(key, field)) config.explicit_keys.insert(section.name(key));
  };
  root.read_enum("sensor", config.sensor, sensor_names());

  YamlSection filter(root.child("filter"), "filter");
  ScanFilterConfig& f = config.filter;
  filter.read_enum("ego", f.ego, kEgoModes);
  read_box(filter, f);
  filter.read("auto_radius", f.auto_radius);
  filter.read("auto_cell", f.auto_cell);
  filter.read("auto_scans", f.auto_scans);
  filter.read("auto_min_share", f.auto_min_share);
  filter.reject_unknown();

  YamlSection voxelizer(root.child("voxelizer"), "voxelizer");
  VoxelizerConfig& v = config.voxelizer;
  read_managed(voxelizer, "voxel_size", v.voxel_size);
  read_managed(voxelizer, "min_points", v.min_points);
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
  read_managed(registration, "sigma_icp", r.sigma_icp);
  registration.read("sigma_cov", r.sigma_cov);
  registration.read("sigma_cov_after_handover", r.sigma_cov_after_handover);
  read_managed(registration, "cov_min_points", r.cov_min_points);
  read_managed(registration, "max_isotropy", r.max_isotropy);
  read_managed(registration, "isotropy_min_share", r.isotropy_min_share);
  registration.read("isotropy_min_information", r.isotropy_min_information);
  read_managed(registration, "line_gate", r.line_gate);
  registration.read("normal_only_ratio", r.normal_only_ratio);
  registration.read("normal_only_iterations", r.normal_only_iterations);
  registration.read("normal_only_start_factor", r.normal_only_start_factor);
  registration.read("normal_only_thickness", r.normal_only_thickness);
  registration.read("lambda", r.lambda);
  registration.read_enum("cov_energy", r.cov_energy, kCovEnergies);
  registration.read_enum("cov_hessian", r.cov_hessian, kCovHessians);
  registration.read("robust_newton", r.robust_newton);
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
  registration.read("regrid_contraction", r.regrid_contraction);
  registration.reject_unknown();

  YamlSection recovery(root.child("recovery"), "recovery");
  RecoveryConfig& rec = config.recovery;
  recovery.read("enabled", rec.enabled);
  recovery.read("trigger_ratio", rec.trigger_ratio);
  read_numbers(recovery, "motion_scales", rec.motion_scales);
  recovery.read("ranked_starts", rec.ranked_starts);
  read_numbers(recovery, "first_speeds", rec.first_speeds);
  recovery.read("first_speeds_max_travel", rec.first_speeds_max_travel);
  recovery.read("first_speeds_skip_reached", rec.first_speeds_skip_reached);
  recovery.read("min_gain", rec.min_gain);
  recovery.read("share_smoothing", rec.share_smoothing);
  read_managed(recovery, "reset_ratio", rec.reset_ratio);
  YamlSection search(recovery.child("global_search"), "recovery.global_search");
  GlobalPoseSearchConfig& gs = rec.global_search;
  search.read("trigger_ratio", gs.trigger_ratio);
  search.read("range_xy", gs.range_xy);
  search.read("range_yaw_deg", gs.range_yaw_deg);
  search.read("coarse_step_xy", gs.coarse_step_xy);
  search.read("coarse_step_yaw_deg", gs.coarse_step_yaw_deg);
  search.read("levels", gs.levels);
  search.read("candidates", gs.candidates);
  search.read("max_sources", gs.max_sources);
  search.read("accept_ratio", gs.accept_ratio);
  search.reject_unknown();
  recovery.reject_unknown();

  YamlSection keyframe(root.child("keyframe"), "keyframe");
  read_managed(keyframe, "distance", config.keyframe.distance);
  keyframe.read("angle_deg", config.keyframe.angle_deg);
  keyframe.reject_unknown();

  YamlSection prediction(root.child("prediction"), "prediction");
  prediction.read("max_interval_ratio", config.prediction.max_interval_ratio);
  prediction.read("learn_max_error_m", config.prediction.learn_max_error_m);
  prediction.read("learn_max_error_deg", config.prediction.learn_max_error_deg);
  prediction.reject_unknown();

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
  YamlSection sweep(deskew.child("sweep_motion"), "deskew.sweep_motion");
  sweep.read("enabled", d.sweep_motion.enabled);
  sweep.read("angular_sigma", d.sweep_motion.angular_sigma);
  sweep.read("linear_sigma", d.sweep_motion.linear_sigma);
  sweep.read("max_time_spread_s", d.sweep_motion.max_time_spread_s);
  sweep.read("max_iterations", d.sweep_motion.max_iterations);
  sweep.read("min_speed_mps", d.sweep_motion.min_speed_mps);
  sweep.reject_unknown();
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
  out << YAML::Key << "sensor" << YAML::Value << sensor_name(c.sensor);
  const ScanFilterConfig& f = c.filter;
  out << YAML::Key << "filter" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "ego" << YAML::Value << enum_name(f.ego, kEgoModes);
  out << YAML::Key << "ego_box" << YAML::Value << YAML::Flow << YAML::BeginSeq << f.ego_box_min.x()
      << f.ego_box_min.y() << f.ego_box_min.z() << f.ego_box_max.x() << f.ego_box_max.y()
      << f.ego_box_max.z() << YAML::EndSeq;
  out << YAML::Key << "auto_radius" << YAML::Value << f.auto_radius;
  out << YAML::Key << "auto_cell" << YAML::Value << f.auto_cell;
  out << YAML::Key << "auto_scans" << YAML::Value << f.auto_scans;
  out << YAML::Key << "auto_min_share" << YAML::Value << f.auto_min_share;
  out << YAML::EndMap;
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
  out << YAML::Key << "sigma_cov_after_handover" << YAML::Value << r.sigma_cov_after_handover;
  out << YAML::Key << "cov_min_points" << YAML::Value << r.cov_min_points;
  out << YAML::Key << "max_isotropy" << YAML::Value << r.max_isotropy;
  out << YAML::Key << "isotropy_min_share" << YAML::Value << r.isotropy_min_share;
  out << YAML::Key << "isotropy_min_information" << YAML::Value << r.isotropy_min_information;
  out << YAML::Key << "line_gate" << YAML::Value << r.line_gate;
  out << YAML::Key << "normal_only_ratio" << YAML::Value << r.normal_only_ratio;
  out << YAML::Key << "normal_only_iterations" << YAML::Value << r.normal_only_iterations;
  out << YAML::Key << "normal_only_start_factor" << YAML::Value << r.normal_only_start_factor;
  out << YAML::Key << "normal_only_thickness" << YAML::Value << r.normal_only_thickness;
  out << YAML::Key << "lambda" << YAML::Value << r.lambda;
  out << YAML::Key << "cov_energy" << YAML::Value << enum_name(r.cov_energy, kCovEnergies);
  out << YAML::Key << "cov_hessian" << YAML::Value << enum_name(r.cov_hessian, kCovHessians);
  out << YAML::Key << "robust_newton" << YAML::Value << r.robust_newton;
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
  out << YAML::Key << "regrid_contraction" << YAML::Value << r.regrid_contraction;
  out << YAML::EndMap;
  out << YAML::Key << "recovery" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << c.recovery.enabled;
  out << YAML::Key << "trigger_ratio" << YAML::Value << c.recovery.trigger_ratio;
  out << YAML::Key << "motion_scales" << YAML::Value << YAML::Flow << c.recovery.motion_scales;
  out << YAML::Key << "ranked_starts" << YAML::Value << c.recovery.ranked_starts;
  out << YAML::Key << "first_speeds" << YAML::Value << YAML::Flow << c.recovery.first_speeds;
  out << YAML::Key << "first_speeds_max_travel" << YAML::Value
      << c.recovery.first_speeds_max_travel;
  out << YAML::Key << "first_speeds_skip_reached" << YAML::Value
      << c.recovery.first_speeds_skip_reached;
  out << YAML::Key << "min_gain" << YAML::Value << c.recovery.min_gain;
  out << YAML::Key << "share_smoothing" << YAML::Value << c.recovery.share_smoothing;
  out << YAML::Key << "reset_ratio" << YAML::Value << c.recovery.reset_ratio;
  const GlobalPoseSearchConfig& gs = c.recovery.global_search;
  out << YAML::Key << "global_search" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "trigger_ratio" << YAML::Value << gs.trigger_ratio;
  out << YAML::Key << "range_xy" << YAML::Value << gs.range_xy;
  out << YAML::Key << "range_yaw_deg" << YAML::Value << gs.range_yaw_deg;
  out << YAML::Key << "coarse_step_xy" << YAML::Value << gs.coarse_step_xy;
  out << YAML::Key << "coarse_step_yaw_deg" << YAML::Value << gs.coarse_step_yaw_deg;
  out << YAML::Key << "levels" << YAML::Value << gs.levels;
  out << YAML::Key << "candidates" << YAML::Value << gs.candidates;
  out << YAML::Key << "max_sources" << YAML::Value << gs.max_sources;
  out << YAML::Key << "accept_ratio" << YAML::Value << gs.accept_ratio;
  out << YAML::EndMap;
  out << YAML::EndMap;
  out << YAML::Key << "keyframe" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "distance" << YAML::Value << c.keyframe.distance;
  out << YAML::Key << "angle_deg" << YAML::Value << c.keyframe.angle_deg;
  out << YAML::EndMap;
  out << YAML::Key << "prediction" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "max_interval_ratio" << YAML::Value << c.prediction.max_interval_ratio;
  out << YAML::Key << "learn_max_error_m" << YAML::Value << c.prediction.learn_max_error_m;
  out << YAML::Key << "learn_max_error_deg" << YAML::Value << c.prediction.learn_max_error_deg;
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
  out << YAML::EndMap;
  out << YAML::Key << "sweep_motion" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << d.sweep_motion.enabled;
  out << YAML::Key << "angular_sigma" << YAML::Value << d.sweep_motion.angular_sigma;
  out << YAML::Key << "linear_sigma" << YAML::Value << d.sweep_motion.linear_sigma;
  out << YAML::Key << "max_time_spread_s" << YAML::Value << d.sweep_motion.max_time_spread_s;
  out << YAML::Key << "max_iterations" << YAML::Value << d.sweep_motion.max_iterations;
  out << YAML::Key << "min_speed_mps" << YAML::Value << d.sweep_motion.min_speed_mps;
  out << YAML::EndMap << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace litamin2
