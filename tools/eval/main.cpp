// litamin2-eval: compares an estimated trajectory with the ground truth (KITTI odometry metric,
// ATE, RPE) and optionally plots both.

#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "common/cli.hpp"
#include "litamin2/eval/ate.hpp"
#include "litamin2/eval/kitti_metrics.hpp"
#include "litamin2/eval/rpe.hpp"
#include "litamin2/eval/time_association.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/trajectory.hpp"
#include "report.hpp"
#include "trajectory_plot.hpp"

namespace {

namespace cli = litamin2::tools;
constexpr const char* kProg = "litamin2-eval";

struct Trajectory {
  std::vector<Eigen::Isometry3d> poses;
  std::vector<double> times;  // TUM only
};

Trajectory read_trajectory(const std::string& path, const std::string& format) {
  Trajectory t;
  if (format == "tum") {
    for (const auto& p : litamin2::io::read_tum(path)) {
      t.poses.push_back(p.pose);
      t.times.push_back(p.time);
    }
  } else {
    t.poses = litamin2::io::read_kitti_poses(path);
  }
  return t;
}

std::string base_name(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// The plot of a report: the estimate as the ATE aligned it, titles with the files and numbers.
litamin2::eval_tool::TrajectoryPlot make_plot(const litamin2::eval_tool::Report& report,
                                              const Trajectory& gt, const Trajectory& est) {
  litamin2::eval_tool::TrajectoryPlot plot;
  plot.ground_truth = gt.poses;
  for (Eigen::Isometry3d pose : est.poses) {
    pose.translation() *= report.ate.scale;
    plot.aligned_estimate.push_back(report.ate.alignment * pose);
  }
  if (gt.times.size() == gt.poses.size()) plot.times = gt.times;
  plot.title = base_name(report.est_path) + " against " + base_name(report.gt_path);
  char text[256];
  std::snprintf(text, sizeof text, "ATE (%s-aligned) RMSE %.3f m, max %.3f m over %zu poses",
                report.alignment.c_str(), report.ate.translation_rmse, report.ate.translation_max,
                report.poses);
  plot.subtitle = text;
  if (report.kitti.valid()) {
    std::snprintf(text, sizeof text, "; KITTI drift %.3f %% / %.4f deg/100 m",
                  report.kitti.translation_percent, report.kitti.rotation_deg_per_100m);
    plot.subtitle += text;
  }
  return plot;
}

const char* kDescription =
    "litamin2-eval: compare an estimated trajectory with the ground truth.\n"
    "\n"
    "Pose i of --est is compared with pose i of --gt; both files must hold the same number of\n"
    "poses (TUM files are paired by line unless --t-max-diff is given; a warning is printed if\n"
    "the timestamps of a pair differ by more than 10 ms).\n"
    "With --t-max-diff S (TUM only, as evo's --t_max_diff) each estimate pose is paired with the\n"
    "ground-truth pose nearest in time, when they are at most S seconds apart; unpaired poses are\n"
    "left out (their counts are printed) and the metrics below use the paired poses only, e.g. a\n"
    "keyframe trajectory against full-rate ground truth. Timestamps must be strictly increasing.\n"
    "\n"
    "Reported:\n"
    "  KITTI odometry metric, as evaluate_odometry.cpp of the official KITTI devkit: segments of\n"
    "    100, 200, ..., 800 m measured along the ground truth, a start every 10 frames, segment "
    "end\n"
    "    = first frame whose distance exceeds start + length; error = inv(inv(E_a) E_b) inv(G_a)\n"
    "    G_b. Per length and averaged over all segments: translation in %, rotation in deg/100 m.\n"
    "    Undefined (printed as n/a / null, with a note) when the ground truth is shorter than\n"
    "    100 m.\n"
    "  ATE: absolute trajectory error after aligning the estimate positions to the ground truth\n"
    "    (closed-form Umeyama/Horn; --align se3 (default), sim3 or none): translation RMSE, mean,\n"
    "    median, max in m and rotation RMSE in deg.\n"
    "  RPE: relative pose error over pairs (i, i + --rpe-delta): translation RMSE/mean in m,\n"
    "    rotation RMSE in deg.\n";

const char* kFooter =
    "Plot (--plot FILE.png|svg|pdf, drawn with Cairo): title with the files, the ATE and the\n"
    "KITTI drift; a top view of the ground truth (dashed black) and the estimate as the ATE\n"
    "aligned it, coloured by its position error (colour bar in metres), start marked green, equal\n"
    "scale on both axes with metre ticks. The two position axes with the largest extent are "
    "shown:\n"
    "x-z for KITTI camera-0 poses (x right, z forward), x-y for z-up poses. Below: the position\n"
    "error over time (TUM) or pose index (KITTI).\n"
    "\n"
    "Exit codes: 0 success; 1 missing/unreadable/malformed file, different pose counts, empty\n"
    "file or plot that cannot be written; 2 bad command line (unknown option, bad value, --plot\n"
    "format, --t-max-diff without --format tum).";

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{kDescription, kProg};
  cli::init_cli(app, kProg);
  app.footer(kFooter);
  std::string gt_path;
  std::string est_path;
  std::string format = "kitti";
  std::string align = "se3";
  std::string plot_path;
  bool json = false;
  std::size_t rpe_delta = 1;
  double t_max_diff = -1.0;
  app.add_option("--gt", gt_path, "Ground-truth trajectory file")->required();
  app.add_option("--est", est_path, "Estimated trajectory file")->required();
  app.add_option("--format", format,
                 "File format of both files: kitti (12 values per line, row-major 3x4 [R|t]) or "
                 "tum (t x y z qx qy qz qw)")
      ->check(CLI::IsMember({"kitti", "tum"}))
      ->capture_default_str();
  app.add_flag("--json", json, "Print one JSON object instead of the table");
  app.add_option("--plot", plot_path, "Write a plot: FILE.png, FILE.svg or FILE.pdf");
  app.add_option("--align", align, "Alignment before the ATE: se3, sim3 or none")
      ->check(CLI::IsMember({"se3", "sim3", "none"}))
      ->capture_default_str();
  app.add_option("--rpe-delta", rpe_delta, "Frame offset of the RPE pairs")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--t-max-diff", t_max_diff,
                 "Pair TUM poses by timestamp: largest difference in seconds (default: by line)")
      ->check(CLI::NonNegativeNumber);
  if (const auto status = cli::parse_cli(app, argc, argv)) return *status;

  if (!plot_path.empty() && litamin2::eval_tool::plot_format(plot_path).empty()) {
    return cli::usage_error(
        kProg,
        "--plot " + plot_path + ": unsupported plot format (use a .png, .svg or .pdf file name)");
  }

  const bool pair_by_time = t_max_diff >= 0.0;
  if (pair_by_time && format != "tum") {
    return cli::usage_error(kProg,
                            "--t-max-diff needs --format tum (KITTI files hold no timestamps)");
  }

  Trajectory gt;
  Trajectory est;
  try {
    gt = read_trajectory(gt_path, format);
  } catch (const litamin2::io::IoError& e) {  // what() starts with the path
    std::cerr << "litamin2-eval: error: cannot read ground truth: " << e.what() << '\n';
    return cli::kExitRuntimeError;
  } catch (const std::exception& e) {
    std::cerr << "litamin2-eval: error: cannot read ground truth " << gt_path << ": " << e.what()
              << '\n';
    return cli::kExitRuntimeError;
  }
  try {
    est = read_trajectory(est_path, format);
  } catch (const litamin2::io::IoError& e) {
    std::cerr << "litamin2-eval: error: cannot read estimate: " << e.what() << '\n';
    return cli::kExitRuntimeError;
  } catch (const std::exception& e) {
    std::cerr << "litamin2-eval: error: cannot read estimate " << est_path << ": " << e.what()
              << '\n';
    return cli::kExitRuntimeError;
  }
  if (gt.poses.empty()) {
    std::cerr << "litamin2-eval: error: ground truth " << gt_path << " holds no poses\n";
    return cli::kExitRuntimeError;
  }
  if (pair_by_time) {
    for (const auto& [trajectory, path] : {std::pair{&gt, gt_path}, std::pair{&est, est_path}}) {
      const std::string error = litamin2::eval::time_series_error(trajectory->times);
      if (!error.empty()) {
        std::cerr << "litamin2-eval: error: " << path << ": " << error << '\n';
        return cli::kExitRuntimeError;
      }
    }
    const auto pairs = litamin2::eval::associate_by_time(gt.times, est.times, t_max_diff);
    if (pairs.size() < 2) {
      std::cerr << "litamin2-eval: error: only " << pairs.size() << " of " << est.poses.size()
                << " estimate poses are within " << t_max_diff << " s of a ground-truth pose\n";
      return cli::kExitRuntimeError;
    }
    Trajectory paired_gt;
    Trajectory paired_est;
    for (const auto& p : pairs) {
      paired_gt.poses.push_back(gt.poses[p.reference_index]);
      paired_gt.times.push_back(gt.times[p.reference_index]);
      paired_est.poses.push_back(est.poses[p.query_index]);
      paired_est.times.push_back(est.times[p.query_index]);
    }
    std::cerr << "litamin2-eval: paired " << pairs.size() << " poses by time (<= " << t_max_diff
              << " s); unpaired: " << est.poses.size() - pairs.size() << " of " << est.poses.size()
              << " estimate, " << gt.poses.size() - pairs.size() << " of " << gt.poses.size()
              << " ground truth\n";
    gt = std::move(paired_gt);
    est = std::move(paired_est);
  }
  if (gt.poses.size() != est.poses.size()) {
    std::cerr << "litamin2-eval: error: pose counts differ: estimate " << est_path << " has "
              << est.poses.size() << " poses, ground truth " << gt_path << " has "
              << gt.poses.size() << '\n';
    return cli::kExitRuntimeError;
  }
  for (std::size_t i = 0; !pair_by_time && i < gt.times.size() && i < est.times.size(); ++i) {
    if (std::abs(gt.times[i] - est.times[i]) > 0.01) {
      std::cerr << "litamin2-eval: warning: timestamps of pose " << i << " differ (" << gt.times[i]
                << " in " << gt_path << ", " << est.times[i] << " in " << est_path
                << "); poses are paired by line\n";
      break;
    }
  }

  namespace le = litamin2::eval;
  litamin2::eval_tool::Report report;
  report.gt_path = gt_path;
  report.est_path = est_path;
  report.format = format;
  report.alignment = align;
  report.poses = gt.poses.size();
  report.gt_length_m = le::trajectory_distances(gt.poses).back();
  report.kitti = le::compute_kitti_metrics(gt.poses, est.poses);
  const le::AteAlignment mode = align == "sim3"   ? le::AteAlignment::kSim3
                                : align == "none" ? le::AteAlignment::kNone
                                                  : le::AteAlignment::kSE3;
  report.ate = le::compute_ate(gt.poses, est.poses, mode);
  report.rpe = le::compute_rpe(gt.poses, est.poses, rpe_delta);

  if (json) {
    litamin2::eval_tool::print_json(std::cout, report);
  } else {
    litamin2::eval_tool::print_table(std::cout, report);
  }

  if (!plot_path.empty()) {
    try {
      litamin2::eval_tool::write_trajectory_plot(plot_path, make_plot(report, gt, est));
    } catch (const std::exception& e) {
      std::cerr << "litamin2-eval: error: cannot write plot: " << e.what() << '\n';
      return cli::kExitRuntimeError;
    }
    if (!json) std::cout << "\nplot written to " << plot_path << '\n';
  }
  return 0;
}
