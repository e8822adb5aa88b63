#include "report.hpp"

#include <cmath>
#include <cstdio>

namespace litamin2::eval_tool {
namespace {

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, value);
  return buf;
}

std::string json_number(double value) {
  if (!std::isfinite(value)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.10g", value);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
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
  out << "{\n"
      << "  \"ground_truth\": " << json_string(r.gt_path) << ",\n"
      << "  \"estimate\": " << json_string(r.est_path) << ",\n"
      << "  \"format\": " << json_string(r.format) << ",\n"
      << "  \"poses\": " << r.poses << ",\n"
      << "  \"gt_length_m\": " << json_number(r.gt_length_m) << ",\n"
      << "  \"kitti\": {\n"
      << "    \"valid\": " << (r.kitti.valid() ? "true" : "false") << ",\n";
  if (!r.kitti.valid()) out << "    \"note\": " << json_string(undefined_note(r)) << ",\n";
  out << "    \"segments\": " << r.kitti.segments << ",\n"
      << "    \"translation_percent\": " << json_number(r.kitti.translation_percent) << ",\n"
      << "    \"rotation_deg_per_100m\": " << json_number(r.kitti.rotation_deg_per_100m) << ",\n"
      << "    \"per_length\": [";
  for (std::size_t i = 0; i < r.kitti.per_length.size(); ++i) {
    const auto& l = r.kitti.per_length[i];
    out << (i ? ",\n" : "\n") << "      {\"length_m\": " << json_number(l.length)
        << ", \"segments\": " << l.segments
        << ", \"translation_percent\": " << json_number(l.translation_percent)
        << ", \"rotation_deg_per_100m\": " << json_number(l.rotation_deg_per_100m) << "}";
  }
  out << "\n    ]\n  },\n"
      << "  \"ate\": {\n"
      << "    \"alignment\": " << json_string(r.alignment) << ",\n"
      << "    \"translation_rmse_m\": " << json_number(r.ate.translation_rmse) << ",\n"
      << "    \"translation_mean_m\": " << json_number(r.ate.translation_mean) << ",\n"
      << "    \"translation_median_m\": " << json_number(r.ate.translation_median) << ",\n"
      << "    \"translation_max_m\": " << json_number(r.ate.translation_max) << ",\n"
      << "    \"rotation_rmse_deg\": " << json_number(r.ate.rotation_rmse_deg) << ",\n"
      << "    \"scale\": " << json_number(r.ate.scale) << "\n"
      << "  },\n"
      << "  \"rpe\": {\n"
      << "    \"delta_frames\": " << r.rpe.delta << ",\n"
      << "    \"pairs\": " << r.rpe.pairs << ",\n"
      << "    \"translation_rmse_m\": " << json_number(r.rpe.translation_rmse) << ",\n"
      << "    \"translation_mean_m\": " << json_number(r.rpe.translation_mean) << ",\n"
      << "    \"rotation_rmse_deg\": " << json_number(r.rpe.rotation_rmse_deg) << "\n"
      << "  }\n"
      << "}\n";
}

}  // namespace litamin2::eval_tool
