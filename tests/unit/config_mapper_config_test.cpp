// The mapper's YAML config: the shipped file holds the defaults, the emitted YAML reads back,
// and bad keys and values are refused with messages naming them.

#include "litamin2/config/mapper_config_yaml.hpp"
#include "litamin2/core/config_error.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

using namespace litamin2;
using namespace litamin2::mapping;

TEST(MappingConfig, ShippedFileHoldsTheDefaults) {
  const MapperConfig shipped = load_mapper_config(LITAMIN2_SOURCE_DIR "/config/mapper.yaml");
  EXPECT_EQ(mapper_config_to_yaml(shipped), mapper_config_to_yaml(MapperConfig{}));
}

TEST(MappingConfig, EmittedYamlReadsBack) {
  MapperConfig config;
  config.place.proximity_radius = 7.5;
  config.place.loop_spacing = 40.0;
  config.place.verification_budget_per_keyframe = 0.25;
  config.place.proximity_max_descriptor_distance = 0.5;
  config.place.proximity_cell_size = 2.5;
  config.place.proximity_cell_keyframes = 0;
  config.graph.local_hold_loops = 3;
  config.graph.full_pass_shift_segments = false;
  config.place.proximity_partner_gap = 250.0;
  config.verification.min_fitness = 0.7;
  config.verification.max_isotropy = 0.05;
  config.graph.threads = 2;
  config.graph.odometry_covariance = OdometryCovariance::kDistance;
  config.graph.tracker_covariance_scale = 4.0;
  config.graph.yaw_drift_window = 500.0;
  config.graph.yaw_drift_min_path = 50.0;
  config.graph.yaw_drift_max_deg_per_100m = 0.75;
  const std::string yaml = mapper_config_to_yaml(config);
  EXPECT_EQ(mapper_config_to_yaml(mapper_config_from_yaml(YAML::Load(yaml))), yaml);
}

TEST(MappingConfig, BadKeysAndValuesAreNamed) {
  auto message = [](const std::string& yaml) {
    try {
      mapper_config_from_yaml(YAML::Load(yaml));
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("verification: {min_fitnes: 0.5}").find("verification.min_fitnes"),
            std::string::npos);
  EXPECT_NE(message("verification: {min_fitness: 1.5}").find("verification.min_fitness"),
            std::string::npos);
  EXPECT_NE(message("verification: {max_isotropy: 0}").find("verification.max_isotropy"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {threads: many}").find("pose_graph.threads"), std::string::npos);
  EXPECT_NE(message("map_voxel_size: -1").find("map_voxel_size"), std::string::npos);
  EXPECT_NE(message("place_recognition: {loop_spacing: -1}").find("place_recognition.loop_spacing"),
            std::string::npos);
  EXPECT_NE(message("place_recognition: {verification_budget_per_keyframe: -1}")
                .find("place_recognition.verification_budget_per_keyframe"),
            std::string::npos);
  EXPECT_NE(message("place_recognition: {proximity_max_descriptor_distance: 2}")
                .find("place_recognition.proximity_max_descriptor_distance"),
            std::string::npos);
  EXPECT_NE(message("place_recognition: {proximity_cell_size: 0}")
                .find("place_recognition.proximity_cell_size"),
            std::string::npos);
  EXPECT_NE(message("place_recognition: {proximity_cell_keyframes: -3}")
                .find("place_recognition.proximity_cell_keyframes"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {local_hold_loops: -1}").find("pose_graph.local_hold_loops"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {local_max_free_keyframes: -1}")
                .find("pose_graph.local_max_free_keyframes"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {odometry_covariance: hessian}")
                .find("pose_graph.odometry_covariance: 'hessian' is not one of: distance, tracker"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {yaw_drift_window: -1}").find("pose_graph.yaw_drift_window"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {yaw_drift_min_path: -5}").find("pose_graph.yaw_drift_min_path"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {yaw_drift_max_deg_per_100m: 0}")
                .find("pose_graph.yaw_drift_max_deg_per_100m"),
            std::string::npos);
  EXPECT_NE(message("pose_graph: {tracker_covariance_scale: 0}")
                .find("pose_graph.tracker_covariance_scale"),
            std::string::npos);
}

TEST(MappingConfig, OdometryCovarianceSource) {
  EXPECT_EQ(MapperConfig{}.graph.odometry_covariance, OdometryCovariance::kTracker);
  const MapperConfig c = mapper_config_from_yaml(
      YAML::Load("pose_graph: {odometry_covariance: distance, tracker_covariance_scale: 3}"));
  EXPECT_EQ(c.graph.odometry_covariance, OdometryCovariance::kDistance);
  EXPECT_DOUBLE_EQ(c.graph.tracker_covariance_scale, 3.0);
}
