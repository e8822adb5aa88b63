// TrackerConfig from YAML: defaults, the shipped file, round trip, and errors that name the
// bad key and value.

#include "litamin2/config/tracker_config_yaml.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>
#include <cstdio>

namespace litamin2 {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    tracker_config_from_yaml(YAML::Load(yaml));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(TrackerConfigYaml, EmptyDocumentGivesDefaults) {
  const TrackerConfig config = tracker_config_from_yaml(YAML::Load("{}"));
  EXPECT_EQ(config.voxelizer.voxel_size, TrackerConfig{}.voxelizer.voxel_size);
  EXPECT_EQ(config.registration.mode, CostMode::kIcpCov);
  EXPECT_EQ(config.registration.sigma_icp, 0.1);
  EXPECT_EQ(config.registration.sigma_cov, 0.3);
  EXPECT_EQ(config.registration.lambda, 1e-6);
}

TEST(TrackerConfigYaml, ShippedFileIsTheDefaults) {
  const TrackerConfig shipped = load_tracker_config(LITAMIN2_SOURCE_DIR "/config/tracker.yaml");
  EXPECT_EQ(tracker_config_to_yaml(shipped), tracker_config_to_yaml(TrackerConfig{}));
  // The keys a sensor preset sets are left to the preset (a key given in a file wins over it).
  EXPECT_TRUE(shipped.explicit_keys.empty());
}

TEST(TrackerConfigYaml, RoundTripKeepsEveryValue) {
  TrackerConfig config;
  config.voxelizer.voxel_size = 2.5;
  config.voxelizer.regularizer.method = RegularizationMethod::kPlane;
  config.registration.mode = CostMode::kIcp;
  config.registration.cov_energy = CovEnergy::kSquared;
  config.registration.correspondence = CorrespondenceMethod::kVoxel27;
  config.keyframe.angle_deg = 7.25;
  config.map.radius = 80.0;
  config.registration.max_isotropy = 0.125;
  config.registration.line_gate = 0.0625;
  config.registration.normal_only_ratio = 0.75;
  config.registration.normal_only_iterations = 3;
  config.registration.normal_only_start_factor = 7.5;
  config.registration.sigma_cov_after_handover = 0.7;
  config.registration.normal_only_thickness = 0.0625;
  config.recovery.reset_ratio = 0.375;
  config.recovery.min_gain = 1.25;
  config.recovery.first_speeds = {-2.5, 7.5};
  config.recovery.first_speeds_max_travel = 0.25;
  config.recovery.first_speeds_skip_reached = false;
  config.recovery.ranked_starts = 3;
  config.recovery.global_search.trigger_ratio = 0.4375;
  config.recovery.global_search.range_xy = 12.5;
  config.recovery.global_search.range_yaw_deg = 30.0;
  config.recovery.global_search.levels = 3;
  config.recovery.global_search.candidates = 5;
  config.recovery.global_search.max_sources = 300;
  config.recovery.global_search.accept_ratio = 0.75;
  config.prediction.learn_max_error_m = 1.5;
  config.prediction.learn_max_error_deg = 7.5;
  config.deskew.sweep_motion.min_speed_mps = 12.5;
  config.registration.isotropy_min_information = 0.625;
  const TrackerConfig back = tracker_config_from_yaml(YAML::Load(tracker_config_to_yaml(config)));
  EXPECT_EQ(tracker_config_to_yaml(back), tracker_config_to_yaml(config));
  EXPECT_EQ(back.voxelizer.voxel_size, 2.5);
  EXPECT_EQ(back.registration.correspondence, CorrespondenceMethod::kVoxel27);
  EXPECT_EQ(back.registration.line_gate, 0.0625);
  EXPECT_EQ(back.registration.normal_only_ratio, 0.75);
  EXPECT_EQ(back.registration.normal_only_iterations, 3);
  EXPECT_EQ(back.registration.normal_only_start_factor, 7.5);
  EXPECT_EQ(back.registration.sigma_cov_after_handover, 0.7);
  EXPECT_EQ(back.registration.normal_only_thickness, 0.0625);
  EXPECT_EQ(back.recovery.reset_ratio, 0.375);
  EXPECT_EQ(back.recovery.min_gain, 1.25);
  EXPECT_EQ(back.recovery.first_speeds, (std::vector<double>{-2.5, 7.5}));
  EXPECT_EQ(back.recovery.first_speeds_max_travel, 0.25);
  EXPECT_FALSE(back.recovery.first_speeds_skip_reached);
  EXPECT_EQ(back.recovery.ranked_starts, 3);
  EXPECT_EQ(back.recovery.global_search.trigger_ratio, 0.4375);
  EXPECT_EQ(back.recovery.global_search.range_xy, 12.5);
  EXPECT_EQ(back.recovery.global_search.range_yaw_deg, 30.0);
  EXPECT_EQ(back.recovery.global_search.levels, 3);
  EXPECT_EQ(back.recovery.global_search.candidates, 5);
  EXPECT_EQ(back.recovery.global_search.max_sources, 300);
  EXPECT_EQ(back.recovery.global_search.accept_ratio, 0.75);
  EXPECT_EQ(back.prediction.learn_max_error_m, 1.5);
  EXPECT_EQ(back.prediction.learn_max_error_deg, 7.5);
  EXPECT_EQ(back.deskew.sweep_motion.min_speed_mps, 12.5);
  EXPECT_EQ(back.registration.isotropy_min_information, 0.625);
}

TEST(TrackerConfigYaml, ErrorsNameKeyAndValue) {
  EXPECT_NE(error_of("voxelizer: {voxel_size: -3}").find("voxelizer.voxel_size: -3"),
            std::string::npos);
  EXPECT_NE(
      error_of("voxelizer: {voxel_size: abc}").find("voxelizer.voxel_size: cannot read 'abc'"),
      std::string::npos);
  EXPECT_NE(error_of("registration: {mode: gicp}").find("registration.mode: 'gicp' is not one of"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {sigma_icpp: 1}").find("registration.sigma_icpp: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("trackr: {}").find("trackr: unknown key"), std::string::npos);
  EXPECT_NE(error_of("registration: 3").find("registration: expected a mapping"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {correspondence: voxel27, max_correspondence_distance: 5}")
                .find("registration.max_correspondence_distance"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {max_isotropy: 0}").find("registration.max_isotropy: 0"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {max_isotropy: 1.5}").find("registration.max_isotropy: 1.5"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {line_gate: -0.1}").find("registration.line_gate: -0.1"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {line_gate: 1}").find("registration.line_gate: 1"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {normal_only_ratio: -0.5}")
                .find("registration.normal_only_ratio: -0.5"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {normal_only_iterations: 0}")
                .find("registration.normal_only_iterations: 0"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {normal_only_thickness: -0.1}")
                .find("registration.normal_only_thickness: -0.1"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {sigma_cov_after_handover: -0.3}")
                .find("registration.sigma_cov_after_handover: -0.3"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {normal_only_start_factor: 0.5}")
                .find("registration.normal_only_start_factor: 0.5"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {first_speeds: [10, 150]}").find("recovery.first_speeds: 150"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {first_speeds: 10}").find("recovery.first_speeds"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {first_speeds_max_travel: -1}")
                .find("recovery.first_speeds_max_travel: -1"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {first_speeds_skip_reached: maybe}")
                .find("recovery.first_speeds_skip_reached"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {ranked_starts: -1}").find("recovery.ranked_starts: -1"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {ranked_starts: 17}").find("recovery.ranked_starts: 17"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {ranked_starts: 1.5}").find("recovery.ranked_starts"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {min_gain: 0.9}").find("recovery.min_gain: 0.9"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {min_gain: 11}").find("recovery.min_gain: 11"), std::string::npos);
  EXPECT_NE(error_of("recovery: {reset_ratio: -0.5}").find("recovery.reset_ratio: -0.5"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {reset_ratio: 1}").find("recovery.reset_ratio: 1"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {global_search: {trigger_ratio: 1}}")
                .find("recovery.global_search.trigger_ratio: 1"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {global_search: {range_xy: 0}}")
                .find("recovery.global_search.range_xy: 0"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {global_search: {coarse_step_xy: 0.01}}")
                .find("recovery.global_search.coarse_step_xy: 0.01"),
            std::string::npos);
  EXPECT_NE(
      error_of("recovery: {global_search: {levels: 0}}").find("recovery.global_search.levels: 0"),
      std::string::npos);
  EXPECT_NE(error_of("recovery: {global_search: {accept_ratio: 0}}")
                .find("recovery.global_search.accept_ratio: 0"),
            std::string::npos);
  EXPECT_NE(error_of("recovery: {global_search: {radius: 3}}").find("global_search.radius"),
            std::string::npos);
  EXPECT_NE(error_of("registration: {max_iterations: 0}").find("registration.max_iterations: 0"),
            std::string::npos);
  EXPECT_NE(
      error_of("prediction: {learn_max_error_m: -1}").find("prediction.learn_max_error_m: -1"),
      std::string::npos);
  EXPECT_NE(error_of("prediction: {learn_max_error_deg: 181}")
                .find("prediction.learn_max_error_deg: 181"),
            std::string::npos);
}

TEST(TrackerConfigYaml, InfinityAndNanAreRejectedForEveryNumber) {
  // Regression (issue 14): +Inf passed validation for 13 keys (sigma_icp, lambda, map.radius,
  // keyframe.distance, voxelizer.max_range, ...) that have only a lower bound.
  const char* keys[] = {"voxelizer: {max_range: %s}",
                        "voxelizer: {min_range: %s}",
                        "voxelizer: {regularization: {min_eigenvalue: %s}}",
                        "map: {radius: %s}",
                        "registration: {sigma_icp: %s}",
                        "registration: {sigma_cov: %s}",
                        "registration: {lambda: %s}",
                        "registration: {rotation_tolerance: %s}",
                        "registration: {translation_tolerance: %s}",
                        "registration: {regrid_translation: %s}",
                        "registration: {regrid_rotation_deg: %s}",
                        "registration: {max_correspondence_distance: %s}",
                        "keyframe: {distance: %s}",
                        "keyframe: {angle_deg: %s}",
                        "recovery: {reset_ratio: %s}",
                        "recovery: {global_search: {trigger_ratio: %s}}",
                        "recovery: {global_search: {range_xy: %s}}",
                        "recovery: {global_search: {accept_ratio: %s}}",
                        "prediction: {learn_max_error_m: %s}",
                        "prediction: {learn_max_error_deg: %s}"};
  for (const char* key : keys) {
    for (const char* value : {".inf", "+.inf", "-.inf", ".nan"}) {
      char yaml[128];
      std::snprintf(yaml, sizeof(yaml), key, value);
      const std::string error = error_of(yaml);
      EXPECT_NE(error.find("is not a finite number"), std::string::npos) << yaml << ": " << error;
    }
  }
}

TEST(TrackerConfigYaml, AMappingAsAKeyIsAConfigError) {
  // Regression (issue 14): `? voxel_size: 3` (a mapping used as a key) threw
  // YAML::TypedBadConversion out of reject_unknown, and the mains aborted (rc 134).
  EXPECT_EQ(error_of("voxelizer:\n  ? voxel_size: 3\n  : 2\n"),
            "voxelizer: a key must be a name, got '{voxel_size: 3}'");
  EXPECT_EQ(error_of("? [a, b]\n: 1\n"), "config: a key must be a name, got '[a, b]'");
}

TEST(TrackerConfigYaml, FileErrorsNameTheFile) {
  try {
    load_tracker_config("/nonexistent/tracker.yaml");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/tracker.yaml"), std::string::npos);
  }
}

}  // namespace
}  // namespace litamin2
