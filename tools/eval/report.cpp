#include "report.hpp"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

namespace litamin2::eval_tool {
namespace {

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, value);
  return buf;
}

/// A JSON number, or null where the figure is undefined (NaN/Inf are not JSON).
nlohmann::ordered_json number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json();
}

std::string undefined_note(const Report& r) {
  const double shortest = r.kitti.per_length.empty() ? 100.0 : r.kitti.per_length.front().length;
  return "ground-truth path is " + fixed(r.gt_length_m, 1) + " m, shorter than the shortest " +
         "segment (" + fixed(shortest, 0) + " m): the KITTI metric is undefined";
}

std::string alignment_label(const std::string& a) {
  if (a == "se3") return "SE(3)-aligned";
  if (a == "sim3") return "Sim(3)-aligned";
  return "not aligned";
}

}  // namespace

void print_table(std::ostream& out, const Report& r) {
  out << "ground truth: " << r.gt_path << "\nestimate:     " << r.est_path
      << "\nformat: " << r.format << ", " << r.poses << " poses, ground-truth path "
      << fixed(r.gt_length_m, 1) << " m\n\n";
  out << "KITTI odometry metric (devkit: segments 100..800 m, a start every 10 frames)\n";
  if (!r.kitti.valid()) {
    out << "  note: " << undefined_note(r) << "\n\n";
  } else {
    char line[160];
    std::snprintf(line, sizeof(line), "  %10s %9s %12s %16s\n", "length [m]", "segments",
                  "trans [%]", "rot [deg/100m]");
    out << line;
    for (const auto& l : r.kitti.per_length) {
      std::snprintf(line, sizeof(line), "  %10.0f %9zu %12s %16s\n", l.length, l.segments,
                    fixed(l.translation_percent, 4).c_str(),
                    fixed(l.rotation_deg_per_100m, 4).c_str());
      out << line;
    }
    std::snprintf(line, sizeof(line), "  %10s %9zu %12s %16s\n\n", "average", r.kitti.segments,
                  fixed(r.kitti.translation_percent, 4).c_str(),
                  fixed(r.kitti.rotation_deg_per_100m, 4).c_str());
    out << line;
  }
  out << "ATE (" << alignment_label(r.alignment) << ", " << r.ate.poses << " poses)\n"
      << "  translation RMSE " << fixed(r.ate.translation_rmse, 4) << " m, mean "
      << fixed(r.ate.translation_mean, 4) << " m, median " << fixed(r.ate.translation_median, 4)
      << " m, max " << fixed(r.ate.translation_max, 4) << " m\n"
      << "  rotation RMSE " << fixed(r.ate.rotation_rmse_deg, 4) << " deg";
  if (r.alignment == "sim3") out << ", scale " << fixed(r.ate.scale, 6);
  out << "\n\nRPE (" << r.rpe.delta << "-frame pairs, " << r.rpe.pairs << " pairs)\n"
      << "  translation RMSE " << fixed(r.rpe.translation_rmse, 4) << " m, mean "
      << fixed(r.rpe.translation_mean, 4) << " m; rotation RMSE "
      << fixed(r.rpe.rotation_rmse_deg, 4) << " deg\n";
}

void print_json(std::ostream& out, const Report& r) {
  using Json = nlohmann::ordered_json;
  Json kitti = {{"valid", r.kitti.valid()}};
  if (!r.kitti.valid()) kitti["note"] = undefined_note(r);
  kitti["segments"] = r.kitti.segments;
  kitti["translation_percent"] = number(r.kitti.translation_percent);
  kitti["rotation_deg_per_100m"] = number(r.kitti.rotation_deg_per_100m);
  kitti["per_length"] = Json::array();
  for (const auto& l : r.kitti.per_length) {
    kitti["per_length"].push_back({{"length_m", number(l.length)},
                                   {"segments", l.segments},
                                   {"translation_percent", number(l.translation_percent)},
                                   {"rotation_deg_per_100m", number(l.rotation_deg_per_100m)}});
  }
  const Json report = {{"ground_truth", r.gt_path},
                       {"estimate", r.est_path},
                       {"format", r.format},
                       {"poses", r.poses},
                       {"gt_length_m", number(r.gt_length_m)},
                       {"kitti", kitti},
                       {"ate",
                        {{"alignment", r.alignment},
                         {"translation_rmse_m", number(r.ate.translation_rmse)},
                         {"translation_mean_m", number(r.ate.translation_mean)},
                         {"translation_median_m", number(r.ate.translation_median)},
                         {"translation_max_m", number(r.ate.translation_max)},
                         {"rotation_rmse_deg", number(r.ate.rotation_rmse_deg)},
                         {"scale", number(r.ate.scale)}}},
                       {"rpe",
                        {{"delta_frames", r.rpe.delta},
                         {"pairs", r.rpe.pairs},
                         {"translation_rmse_m", number(r.rpe.translation_rmse)},
                         {"translation_mean_m", number(r.rpe.translation_mean)},
                         {"rotation_rmse_deg", number(r.rpe.rotation_rmse_deg)}}}};
  // Invalid UTF-8 in a file name is replaced, not thrown (the report is still written).
  out << report.dump(2, ' ', false, Json::error_handler_t::replace) << '\n';
}

}  // namespace litamin2::eval_tool
