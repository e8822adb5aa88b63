#include "litamin2/mapping/mapper_config.hpp"

#include "litamin2/core/config_error.hpp"

namespace litamin2::mapping {

void validate(const MapperConfig& c) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw ConfigError("mapper config: " + what);
  };
  require(c.place.rings >= 2 && c.place.sectors >= 4, "place_recognition grid too small");
  require(c.place.max_range > 0.0, "place_recognition.max_range must be positive");
  require(c.place.ring_key_candidates >= 1, "place_recognition.ring_key_candidates must be >= 1");
  require(c.place.proximity_max_descriptor_distance >= 0.0 &&
              c.place.proximity_max_descriptor_distance <= 1.0,
          "place_recognition.proximity_max_descriptor_distance must be in [0, 1]");
  require(c.place.proximity_cell_size > 0.0,
          "place_recognition.proximity_cell_size must be positive");
  require(c.place.proximity_cell_keyframes >= 0,
          "place_recognition.proximity_cell_keyframes must be >= 0");
  require(c.place.verification_budget_per_keyframe >= 0.0,
          "place_recognition.verification_budget_per_keyframe must be >= 0");
  require(c.verification.min_fitness >= 0.0 && c.verification.min_fitness <= 1.0,
          "verification.min_fitness must be in [0, 1]");
  require(c.map_voxel_size > 0.0, "map_voxel_size must be positive");
  require(c.place.search_spacing >= 0.0, "place_recognition.search_spacing must be >= 0");
  require(c.place.loop_spacing >= 0.0, "place_recognition.loop_spacing must be >= 0");
  require(c.place.merge_confirmations >= 1, "place_recognition.merge_confirmations must be >= 1");
  require(c.place.merge_min_separation >= 0.0,
          "place_recognition.merge_min_separation must be >= 0");
  require(c.place.merge_agreement_m > 0.0, "place_recognition.merge_agreement_m must be positive");
  require(c.place.merge_agreement_per_m >= 0.0,
          "place_recognition.merge_agreement_per_m must be >= 0");
  require(c.place.merge_agreement_deg > 0.0 && c.place.merge_agreement_deg <= 180.0,
          "place_recognition.merge_agreement_deg must be in (0, 180]");
  require(c.graph.local_max_keyframes >= 1, "pose_graph.local_max_keyframes must be >= 1");
  require(c.graph.local_hops >= 0, "pose_graph.local_hops must be >= 0");
  require(c.graph.local_hold_loops >= 0, "pose_graph.local_hold_loops must be >= 0");
  require(c.graph.local_max_free_keyframes >= 0,
          "pose_graph.local_max_free_keyframes must be >= 0 (0 = no bound)");
  require(c.graph.segment_keyframes >= 1, "pose_graph.segment_keyframes must be >= 1");
  require(c.graph.full_pass_min_shift >= 0.0 && c.graph.full_pass_min_turn_deg >= 0.0,
          "pose_graph.full_pass_min_shift and full_pass_min_turn_deg must be >= 0");
  require(c.graph.full_pass_max_segments >= 0,
          "pose_graph.full_pass_max_segments must be >= 0 (0 = no bound)");
  require(c.graph.yaw_drift_window >= 0.0 && c.graph.yaw_drift_min_path >= 0.0,
          "pose_graph.yaw_drift_window and yaw_drift_min_path must be >= 0 (window 0 = off)");
  require(c.graph.yaw_drift_max_deg_per_100m > 0.0,
          "pose_graph.yaw_drift_max_deg_per_100m must be positive");
  require(c.graph.iterative_min_free_poses >= 0,
          "pose_graph.iterative_min_free_poses must be >= 0 (0 = never)");
}

}  // namespace litamin2::mapping
