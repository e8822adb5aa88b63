// litamin2-covariance-check: how well the tracker's covariance describes the odometry's real
// error. Runs the tracker over a KITTI-layout sequence with ground truth and, for each pair of
// consecutive keyframes (a, b), compares the error e of the relative pose T_a^-1 T_b in the pose
// graph's residual coordinates with the covariance C the mapper gives that edge
// (mapping::relative_pose_covariance of b's tracker covariance). For a consistent covariance
// the normalised error e^T C^-1 e averages 6 (chi-square with 6 degrees of freedom); the
// standard-deviation factor that makes it so, sqrt(mean / 6), is the calibrated
// pose_graph.tracker_covariance_scale. The distance model's sigmas are checked the same way.

#include "common/cli.hpp"
#include "common/frame_range.hpp"
#include "litamin2/config/tracker_config_yaml.hpp"
#include "litamin2/core/config_error.hpp"
#include "litamin2/core/tracker.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/mapping/odometry_covariance.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace litamin2;

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

struct Sample {
  Eigen::Isometry3d estimate, truth;
  Matrix6d covariance;
};

void report(const char* name, std::vector<double> nees) {
  std::sort(nees.begin(), nees.end());
  double mean = 0.0;
  for (double x : nees) mean += x;
  mean /= static_cast<double>(nees.size());
  std::printf("%-8s e^T C^-1 e / 6: mean %.4g, median %.4g, p90 %.4g; calibrated scale %.3g\n",
              name, mean / 6.0, nees[nees.size() / 2] / 6.0, nees[nees.size() * 9 / 10] / 6.0,
              std::sqrt(mean / 6.0));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "litamin2-covariance-check: the tracker's relative-pose covariance against ground truth\n"
      "Consistency of the tracker's relative-pose covariance with a sequence's ground "
      "truth; prints the calibrated pose_graph.tracker_covariance_scale"};
  litamin2::tools::init_cli(app, "litamin2-covariance-check");
  std::string input, config_file, mode, frames;
  app.add_option("INPUT", input, "KITTI sequence folder with poses.txt and calib.txt")->required();
  app.add_option("-c,--config", config_file, "Tracker config YAML");
  app.add_option("--mode", mode, "icp or icp+cov (overrides the config)")
      ->check(CLI::IsMember({"icp", "icp+cov"}));
  litamin2::tools::add_frames_option(app, frames, "frames");
  if (const auto status = litamin2::tools::parse_cli(app, argc, argv)) return *status;
  std::string frames_error;
  const auto range = litamin2::tools::parse_frame_range(frames, &frames_error);
  if (!range) return litamin2::tools::usage_error(app.get_name(), frames_error);

  try {
    TrackerConfig config = config_file.empty() ? TrackerConfig{} : load_tracker_config(config_file);
    if (mode == "icp") config.registration.mode = CostMode::kIcp;
    if (mode == "icp+cov") config.registration.mode = CostMode::kIcpCov;
    const io::ScanSequence sequence(input);
    if (!sequence.ground_truth_cam() || !sequence.velo_to_cam())
      throw std::runtime_error(input + ": needs poses.txt and calib.txt");
    const Eigen::Isometry3d tr = *sequence.velo_to_cam();
    const auto& gt = *sequence.ground_truth_cam();
    const auto selected = range->within(sequence.size());
    if (!selected)
      return litamin2::tools::usage_error(
          app.get_name(),
          "--frames " + frames + " selects no frame of " + std::to_string(sequence.size()));
    const auto [first, last] = *selected;

    Tracker tracker(config);
    std::vector<Sample> keyframes;
    for (std::size_t i = first; i < last; ++i) {
      const FrameResult f = tracker.process(sequence.load(i));
      if (f.keyframe) keyframes.push_back({f.pose, tr.inverse() * gt[i] * tr, f.covariance});
    }

    const mapping::PoseGraphConfig graph;
    std::vector<double> tracker_nees, distance_nees;
    Vector6d error_sq = Vector6d::Zero(), tracker_var = Vector6d::Zero();
    for (std::size_t k = 1; k < keyframes.size(); ++k) {
      const Sample &a = keyframes[k - 1], &b = keyframes[k];
      if (b.covariance.isZero(0.0)) continue;
      const Eigen::Isometry3d estimate = a.estimate.inverse() * b.estimate;
      const Eigen::Isometry3d truth = a.truth.inverse() * b.truth;
      Vector6d e;  // residual coordinates (pose_graph.cpp)
      e.head<3>() = truth.translation() - estimate.translation();
      const Eigen::AngleAxisd rotation(estimate.linear().transpose() * truth.linear());
      e.tail<3>() = rotation.angle() * rotation.axis();
      const Matrix6d c = mapping::relative_pose_covariance(a.estimate, b.estimate, b.covariance);
      tracker_nees.push_back(e.dot(c.ldlt().solve(e)));
      const double d = estimate.translation().norm();
      const double st = std::max(graph.odometry_translation_sigma_min,
                                 graph.odometry_translation_sigma_per_m * d);
      const double sr = std::max(graph.odometry_rotation_sigma_min_deg,
                                 graph.odometry_rotation_sigma_deg_per_m * d) *
                        M_PI / 180.0;
      Vector6d sigma;
      sigma << st, st, st, sr, sr, sr;
      distance_nees.push_back(e.cwiseQuotient(sigma).squaredNorm());
      error_sq += e.cwiseAbs2();
      tracker_var += c.diagonal();
    }
    if (tracker_nees.empty()) throw std::runtime_error("no pair of registered keyframes");
    const double m = static_cast<double>(tracker_nees.size());
    std::printf("%zu keyframe pairs over %zu frames\n", tracker_nees.size(), last - first);
    report("tracker", tracker_nees);
    report("distance", distance_nees);
    const Vector6d rms_e = (error_sq / m).cwiseSqrt(), rms_s = (tracker_var / m).cwiseSqrt();
    std::printf("RMS error:          t %.4f %.4f %.4f m, r %.4f %.4f %.4f deg\n", rms_e(0),
                rms_e(1), rms_e(2), rms_e(3) * 180 / M_PI, rms_e(4) * 180 / M_PI,
                rms_e(5) * 180 / M_PI);
    std::printf("RMS tracker sigma:  t %.4f %.4f %.4f m, r %.4f %.4f %.4f deg\n", rms_s(0),
                rms_s(1), rms_s(2), rms_s(3) * 180 / M_PI, rms_s(4) * 180 / M_PI,
                rms_s(5) * 180 / M_PI);
  } catch (const ConfigError& e) {
    return litamin2::tools::usage_error(app.get_name(),
                                        std::string("invalid configuration: ") + e.what());
  } catch (const std::exception& e) {
    return litamin2::tools::runtime_error(app.get_name(), e.what());
  }
  return 0;
}
