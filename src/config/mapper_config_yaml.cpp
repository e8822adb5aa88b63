#include "litamin2/config/mapper_config_yaml.hpp"

#include "litamin2/config/config_file.hpp"
#include "litamin2/config/yaml_section.hpp"

#include <yaml-cpp/yaml.h>

namespace litamin2::mapping {

using config::load_config_file;
using config::YamlSection;

MapperConfig mapper_config_from_yaml(const YAML::Node& node) {
  MapperConfig config;
  YamlSection root(node, "");

  YamlSection place(root.child("place_recognition"), "place_recognition");
  PlaceRecognitionConfig& p = config.place;
  place.read_range("rings", p.rings, 2, 200);
  place.read_range("sectors", p.sectors, 4, 720);
  place.read_range("max_range", p.max_range, 1.0, 1000.0);
  place.read_range("ring_key_candidates", p.ring_key_candidates, 1, 1000);
  place.read_range("max_descriptor_distance", p.max_descriptor_distance, 0.0, 1.0);
  place.read_range("min_travel_gap", p.min_travel_gap, 0.0, 1e6);
  place.read_range("proximity_radius", p.proximity_radius, 0.0, 1e4);
  place.read_range("proximity_cell_size", p.proximity_cell_size, 0.1, 1e4);
  place.read_range("proximity_cell_keyframes", p.proximity_cell_keyframes, 0, 1000000);
  place.read_range("proximity_partner_gap", p.proximity_partner_gap, 0.0, 1e6);
  place.read_range("verification_budget_per_keyframe", p.verification_budget_per_keyframe, 0.0,
                   1e3);
  place.read_range("proximity_max_descriptor_distance", p.proximity_max_descriptor_distance, 0.0,
                   1.0);
  place.read_enum<PlaceSearch>(
      "search", p.search, {{"indexed", PlaceSearch::kIndexed}, {"linear", PlaceSearch::kLinear}});
  place.read_range("search_spacing", p.search_spacing, 0.0, 1e4);
  place.read_range("loop_spacing", p.loop_spacing, 0.0, 1e5);
  place.read_range("merge_confirmations", p.merge_confirmations, 1, 100);
  place.read_range("merge_min_separation", p.merge_min_separation, 0.0, 1e5);
  place.read_range("merge_agreement_m", p.merge_agreement_m, 1e-3, 1e4);
  place.read_range("merge_agreement_per_m", p.merge_agreement_per_m, 0.0, 1.0);
  place.read_range("merge_agreement_deg", p.merge_agreement_deg, 1e-3, 180.0);
  place.reject_unknown();

  YamlSection verification(root.child("verification"), "verification");
  LoopVerificationConfig& v = config.verification;
  verification.read_range("submap_neighbours", v.submap_neighbours, 0, 100);
  verification.read_range("sigma_icp", v.sigma_icp, 1e-3, 100.0);
  verification.read_range("max_isotropy", v.max_isotropy, 1e-6, 1.0);
  verification.read_range("fitness_distance", v.fitness_distance, 1e-3, 100.0);
  verification.read_range("min_fitness", v.min_fitness, 0.0, 1.0);
  verification.read_range("max_rmse", v.max_rmse, 1e-3, 100.0);
  verification.read_range("rotation_sigma_deg", v.rotation_sigma_deg, 1e-4, 180.0);
  verification.read_range("translation_sigma", v.translation_sigma, 1e-4, 100.0);
  verification.reject_unknown();

  YamlSection graph(root.child("pose_graph"), "pose_graph");
  PoseGraphConfig& g = config.graph;
  graph.read_enum<OdometryCovariance>(
      "odometry_covariance", g.odometry_covariance,
      {{"distance", OdometryCovariance::kDistance}, {"tracker", OdometryCovariance::kTracker}});
  graph.read_range("tracker_covariance_scale", g.tracker_covariance_scale, 1e-3, 1e6);
  graph.read_range("tracker_translation_sigma_min", g.tracker_translation_sigma_min, 1e-6, 100.0);
  graph.read_range("tracker_rotation_sigma_min_deg", g.tracker_rotation_sigma_min_deg, 1e-6, 180.0);
  graph.read_range("odometry_translation_sigma_per_m", g.odometry_translation_sigma_per_m, 1e-6,
                   10.0);
  graph.read_range("odometry_rotation_sigma_deg_per_m", g.odometry_rotation_sigma_deg_per_m, 1e-6,
                   180.0);
  graph.read_range("odometry_translation_sigma_min", g.odometry_translation_sigma_min, 1e-6, 100.0);
  graph.read_range("odometry_rotation_sigma_min_deg", g.odometry_rotation_sigma_min_deg, 1e-6,
                   180.0);
  graph.read_range("loop_loss_scale", g.loop_loss_scale, 1e-3, 1e3);
  graph.read_range("loop_consistency_sigmas", g.loop_consistency_sigmas, 0.1, 1e6);
  graph.read_range("level_prior_sigma_deg", g.level_prior_sigma_deg, 0.0, 90.0);
  graph.read_range("local_max_keyframes", g.local_max_keyframes, 1, 1'000'000);
  graph.read_range("local_hops", g.local_hops, 0, 10'000);
  graph.read_range("local_hold_loops", g.local_hold_loops, 0, 1'000'000);
  graph.read_range("local_max_free_keyframes", g.local_max_free_keyframes, 0, 1'000'000);
  graph.read("local_widen_for_loops", g.local_widen_for_loops);
  graph.read_range("segment_keyframes", g.segment_keyframes, 1, 100'000);
  graph.read("full_pass_shift_segments", g.full_pass_shift_segments);
  graph.read_range("full_pass_max_segments", g.full_pass_max_segments, 0, 100'000'000);
  graph.read_range("full_pass_min_shift", g.full_pass_min_shift, 0.0, 10.0);
  graph.read_range("full_pass_min_turn_deg", g.full_pass_min_turn_deg, 0.0, 10.0);
  graph.read_range("yaw_drift_window", g.yaw_drift_window, 0.0, 1e7);
  graph.read_range("yaw_drift_min_path", g.yaw_drift_min_path, 0.0, 1e7);
  graph.read_range("yaw_drift_max_deg_per_100m", g.yaw_drift_max_deg_per_100m, 1e-6, 1e4);
  graph.read_range("iterative_min_free_poses", g.iterative_min_free_poses, 0, 100'000'000);
  graph.read_range("max_iterations", g.max_iterations, 1, 10000);
  graph.read_range("threads", g.threads, 1, 256);
  graph.reject_unknown();

  root.read_range("map_voxel_size", config.map_voxel_size, 0.05, 100.0);
  root.reject_unknown();
  return config;
}

MapperConfig load_mapper_config(const std::string& path) {
  return load_config_file(path, [](const YAML::Node& node) {
    return mapper_config_from_yaml(node.IsMap() && node["mapper"] ? node["mapper"] : node);
  });
}

std::string mapper_config_to_yaml(const MapperConfig& c) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap;
  out << YAML::Key << "place_recognition" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "rings" << YAML::Value << c.place.rings;
  out << YAML::Key << "sectors" << YAML::Value << c.place.sectors;
  out << YAML::Key << "max_range" << YAML::Value << c.place.max_range;
  out << YAML::Key << "ring_key_candidates" << YAML::Value << c.place.ring_key_candidates;
  out << YAML::Key << "max_descriptor_distance" << YAML::Value << c.place.max_descriptor_distance;
  out << YAML::Key << "min_travel_gap" << YAML::Value << c.place.min_travel_gap;
  out << YAML::Key << "proximity_radius" << YAML::Value << c.place.proximity_radius;
  out << YAML::Key << "proximity_cell_size" << YAML::Value << c.place.proximity_cell_size;
  out << YAML::Key << "proximity_cell_keyframes" << YAML::Value << c.place.proximity_cell_keyframes;
  out << YAML::Key << "proximity_partner_gap" << YAML::Value << c.place.proximity_partner_gap;
  out << YAML::Key << "verification_budget_per_keyframe" << YAML::Value
      << c.place.verification_budget_per_keyframe;
  out << YAML::Key << "proximity_max_descriptor_distance" << YAML::Value
      << c.place.proximity_max_descriptor_distance;
  out << YAML::Key << "search" << YAML::Value
      << (c.place.search == PlaceSearch::kLinear ? "linear" : "indexed");
  out << YAML::Key << "search_spacing" << YAML::Value << c.place.search_spacing;
  out << YAML::Key << "loop_spacing" << YAML::Value << c.place.loop_spacing;
  out << YAML::Key << "merge_confirmations" << YAML::Value << c.place.merge_confirmations;
  out << YAML::Key << "merge_min_separation" << YAML::Value << c.place.merge_min_separation;
  out << YAML::Key << "merge_agreement_m" << YAML::Value << c.place.merge_agreement_m;
  out << YAML::Key << "merge_agreement_per_m" << YAML::Value << c.place.merge_agreement_per_m;
  out << YAML::Key << "merge_agreement_deg" << YAML::Value << c.place.merge_agreement_deg;
  out << YAML::EndMap;
  out << YAML::Key << "verification" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "submap_neighbours" << YAML::Value << c.verification.submap_neighbours;
  out << YAML::Key << "sigma_icp" << YAML::Value << c.verification.sigma_icp;
  out << YAML::Key << "max_isotropy" << YAML::Value << c.verification.max_isotropy;
  out << YAML::Key << "fitness_distance" << YAML::Value << c.verification.fitness_distance;
  out << YAML::Key << "min_fitness" << YAML::Value << c.verification.min_fitness;
  out << YAML::Key << "max_rmse" << YAML::Value << c.verification.max_rmse;
  out << YAML::Key << "rotation_sigma_deg" << YAML::Value << c.verification.rotation_sigma_deg;
  out << YAML::Key << "translation_sigma" << YAML::Value << c.verification.translation_sigma;
  out << YAML::EndMap;
  out << YAML::Key << "pose_graph" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "odometry_covariance" << YAML::Value
      << (c.graph.odometry_covariance == OdometryCovariance::kTracker ? "tracker" : "distance");
  out << YAML::Key << "tracker_covariance_scale" << YAML::Value << c.graph.tracker_covariance_scale;
  out << YAML::Key << "tracker_translation_sigma_min" << YAML::Value
      << c.graph.tracker_translation_sigma_min;
  out << YAML::Key << "tracker_rotation_sigma_min_deg" << YAML::Value
      << c.graph.tracker_rotation_sigma_min_deg;
  out << YAML::Key << "odometry_translation_sigma_per_m" << YAML::Value
      << c.graph.odometry_translation_sigma_per_m;
  out << YAML::Key << "odometry_rotation_sigma_deg_per_m" << YAML::Value
      << c.graph.odometry_rotation_sigma_deg_per_m;
  out << YAML::Key << "odometry_translation_sigma_min" << YAML::Value
      << c.graph.odometry_translation_sigma_min;
  out << YAML::Key << "odometry_rotation_sigma_min_deg" << YAML::Value
      << c.graph.odometry_rotation_sigma_min_deg;
  out << YAML::Key << "loop_loss_scale" << YAML::Value << c.graph.loop_loss_scale;
  out << YAML::Key << "loop_consistency_sigmas" << YAML::Value << c.graph.loop_consistency_sigmas;
  out << YAML::Key << "level_prior_sigma_deg" << YAML::Value << c.graph.level_prior_sigma_deg;
  out << YAML::Key << "local_max_keyframes" << YAML::Value << c.graph.local_max_keyframes;
  out << YAML::Key << "local_hops" << YAML::Value << c.graph.local_hops;
  out << YAML::Key << "local_hold_loops" << YAML::Value << c.graph.local_hold_loops;
  out << YAML::Key << "local_max_free_keyframes" << YAML::Value << c.graph.local_max_free_keyframes;
  out << YAML::Key << "local_widen_for_loops" << YAML::Value << c.graph.local_widen_for_loops;
  out << YAML::Key << "segment_keyframes" << YAML::Value << c.graph.segment_keyframes;
  out << YAML::Key << "full_pass_shift_segments" << YAML::Value << c.graph.full_pass_shift_segments;
  out << YAML::Key << "full_pass_max_segments" << YAML::Value << c.graph.full_pass_max_segments;
  out << YAML::Key << "full_pass_min_shift" << YAML::Value << c.graph.full_pass_min_shift;
  out << YAML::Key << "full_pass_min_turn_deg" << YAML::Value << c.graph.full_pass_min_turn_deg;
  out << YAML::Key << "yaw_drift_window" << YAML::Value << c.graph.yaw_drift_window;
  out << YAML::Key << "yaw_drift_min_path" << YAML::Value << c.graph.yaw_drift_min_path;
  out << YAML::Key << "yaw_drift_max_deg_per_100m" << YAML::Value
      << c.graph.yaw_drift_max_deg_per_100m;
  out << YAML::Key << "iterative_min_free_poses" << YAML::Value << c.graph.iterative_min_free_poses;
  out << YAML::Key << "max_iterations" << YAML::Value << c.graph.max_iterations;
  out << YAML::Key << "threads" << YAML::Value << c.graph.threads;
  out << YAML::EndMap;
  out << YAML::Key << "map_voxel_size" << YAML::Value << c.map_voxel_size;
  out << YAML::EndMap;
  return out.c_str();
}

}  // namespace litamin2::mapping
