// litamin2-scan-agreement: how well a path makes consecutive scans of a folder agree
// (eval/scan_agreement.hpp), for real data without ground truth: per pair of files the median
// nearest-neighbour distance under the path's motion, then its median, 90th percentile and the
// pairs below --agree (docs/accuracy.md, "Breaks in the real VLP-16 drive").

#include "common/cli.hpp"
#include "common/frame_range.hpp"
#include "litamin2/eval/scan_agreement.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/io/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

using namespace litamin2;

int main(int argc, char** argv) {
  CLI::App app{
      "litamin2-scan-agreement: how well consecutive scans agree under a path\n"
      "Agreement of consecutive scans under a path: median distance from each scan's points, "
      "moved by the path's motion, to the previous scan's nearest points (no ground truth)"};
  tools::init_cli(app, "litamin2-scan-agreement");
  std::string input, poses_file, frames;
  eval::ScanAgreementConfig config;
  double agree = 0.2;
  bool per_frame = false, json = false;
  app.add_option("SCANS", input, "Folder of scans (KITTI .bin or .pcd, as litamin2-odometry)")
      ->required();
  app.add_option("POSES", poses_file,
                 "Path in KITTI 3x4 form, one sensor pose per scan in the first scan's frame "
                 "(litamin2-odometry's poses_kitti.txt)")
      ->required();
  tools::add_frames_option(app, frames, "scans");
  app.add_option("--min-range", config.min_range, "Points nearer than this are left out [m]")
      ->capture_default_str();
  app.add_option("--max-range", config.max_range, "Points farther than this are left out [m]")
      ->capture_default_str();
  app.add_option("--min-z", config.min_z,
                 "Points below this height in the sensor frame are left out [m] (the ground)")
      ->capture_default_str();
  app.add_option("--stride", config.stride, "Every n-th kept point is measured")
      ->capture_default_str();
  app.add_option("--agree", agree, "A pair below this median distance agrees [m]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app.add_flag("--per-frame", per_frame, "Print one line per pair");
  app.add_flag("--json", json, "Print the summary as JSON");
  if (const auto status = tools::parse_cli(app, argc, argv)) return *status;
  std::string frames_error;
  const auto range = tools::parse_frame_range(frames, &frames_error);
  if (!range) return tools::usage_error(app.get_name(), frames_error);
  try {
    eval::validate(config);
  } catch (const std::invalid_argument& e) {
    return tools::usage_error(app.get_name(), e.what());
  }

  try {
    const io::ScanSequence sequence(input);
    const auto poses = io::read_kitti_poses(poses_file);
    if (poses.size() != sequence.size())
      throw std::runtime_error(poses_file + ": " + std::to_string(poses.size()) + " poses for " +
                               std::to_string(sequence.size()) + " scans");
    const auto selected = range->within(sequence.size());
    if (!selected || selected->second - selected->first < 2)
      return tools::usage_error(app.get_name(), "--frames " + frames + " selects fewer than 2 of " +
                                                    std::to_string(sequence.size()) + " scans");
    const auto [first, last] = *selected;
    std::vector<double> medians;
    int empty = 0;
    PointCloud previous = sequence.load(first);
    for (std::size_t i = first + 1; i < last; ++i) {
      PointCloud scan = sequence.load(i);
      const eval::ScanAgreement a =
          eval::scan_agreement(previous, scan, poses[i - 1].inverse() * poses[i], config);
      if (per_frame) std::printf("%zu %.4f %d\n", i, a.median_m, a.measured);
      if (std::isnan(a.median_m))
        ++empty;
      else
        medians.push_back(a.median_m);
      previous = std::move(scan);
    }
    const std::size_t pairs = last - first - 1;
    const std::size_t agreeing = static_cast<std::size_t>(
        std::count_if(medians.begin(), medians.end(), [&](double m) { return m < agree; }));
    std::sort(medians.begin(), medians.end());
    const auto q = [&](double f) {
      return medians.empty() ? std::nan("")
                             : medians[std::min(medians.size() - 1,
                                                static_cast<std::size_t>(f * medians.size()))];
    };
    if (json) {
      std::printf(
          "{\"pairs\": %zu, \"without_points\": %d, \"median_m\": %.4f, \"p90_m\": %.4f, "
          "\"agree_m\": %.3f, \"agreeing\": %zu}\n",
          pairs, empty, q(0.5), q(0.9), agree, agreeing);
    } else {
      std::printf("%zu pairs (%d without points): median %.3f m, p90 %.3f m, %zu below %.2f m\n",
                  pairs, empty, q(0.5), q(0.9), agreeing, agree);
    }
  } catch (const std::exception& e) {
    return tools::runtime_error(app.get_name(), e.what());
  }
  return 0;
}
