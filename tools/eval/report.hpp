#pragma once
/// Text table and JSON output of litamin2-eval.

#include <ostream>
#include <string>

#include "litamin2/eval/ate.hpp"
#include "litamin2/eval/kitti_metrics.hpp"
#include "litamin2/eval/rpe.hpp"

namespace litamin2::eval_tool {

/// Everything litamin2-eval reports for one pair of trajectories.
struct Report {
  std::string gt_path;
  std::string est_path;
  std::string format;     ///< "kitti" or "tum"
  std::string alignment;  ///< "se3", "sim3" or "none"
  std::size_t poses = 0;
  double gt_length_m = 0.0;  ///< path length of the ground truth
  eval::KittiMetrics kitti;
  eval::AteResult ate;
  eval::RpeResult rpe;
};

/// Human-readable table (per-length KITTI errors, averages, ATE, RPE).
void print_table(std::ostream& out, const Report& report);

/// One JSON object with the same numbers; undefined values (NaN) are written as null.
void print_json(std::ostream& out, const Report& report);

}  // namespace litamin2::eval_tool
