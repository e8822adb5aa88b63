#include "odometry/run_stats.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

namespace litamin2::tools {

void RunStats::add(const FrameResult& frame) {
  total_ms_.push_back(frame.times.total_ms());
  sum_.voxelize_ms += frame.times.voxelize_ms;
  sum_.register_ms += frame.times.register_ms;
  sum_.map_update_ms += frame.times.map_update_ms;
  sum_.deskew_ms += frame.times.deskew_ms;
  deskewed_ += frame.deskewed ? 1 : 0;
  keyframes_ += frame.keyframe ? 1 : 0;
  failures_ += (!frame.registered && total_ms_.size() > 1) ? 1 : 0;
  distributions_ += static_cast<std::size_t>(frame.source_distributions);
  iterations_ += static_cast<std::size_t>(frame.iterations);
  voxelizations_ += static_cast<std::size_t>(frame.voxelizations);
  regrid_stops_ += frame.regrid_stopped ? 1 : 0;
  retries_ += frame.retried ? 1 : 0;
  recoveries_ += frame.recovered ? 1 : 0;
  map_resets_ += frame.map_reset ? 1 : 0;
  self_hits_ += static_cast<std::size_t>(frame.self_hits);
}

void RunStats::add_skipped(std::size_t index, const std::string& path, const std::string& error) {
  skipped_.push_back({index, path, error});
}

namespace {

/// `text` as a JSON string.
std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char code[8];
      std::snprintf(code, sizeof(code), "\\u%04x", c);
      out += code;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

double RunStats::frames_per_second() const {
  const double total = std::accumulate(total_ms_.begin(), total_ms_.end(), 0.0);
  return total > 0.0 ? 1000.0 * static_cast<double>(total_ms_.size()) / total : 0.0;
}

double RunStats::percentile_ms(double p) const {
  if (total_ms_.empty()) return 0.0;
  std::vector<double> sorted = total_ms_;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t index = static_cast<std::size_t>(
      std::min<double>(sorted.size() - 1, std::floor(p / 100.0 * (sorted.size() - 1) + 0.5)));
  return sorted[index];
}

double RunStats::max_ms() const {
  return total_ms_.empty() ? 0.0 : *std::max_element(total_ms_.begin(), total_ms_.end());
}

std::string RunStats::to_json(const std::string& mode, const std::string& sensor, double voxel_size,
                              int threads, double wall_seconds,
                              const std::optional<Accuracy>& accuracy) const {
  const double n = std::max<double>(1.0, static_cast<double>(frames()));
  std::ostringstream out;
  out.precision(6);
  out << "{\n"
      << "  \"frames\": " << frames() << ",\n"
      << "  \"mode\": \"" << mode << "\",\n"
      << "  \"sensor\": \"" << sensor << "\",\n"
      << "  \"voxel_size\": " << voxel_size << ",\n"
      << "  \"threads\": " << threads << ",\n"
      << "  \"frames_per_second\": " << frames_per_second() << ",\n"
      << "  \"wall_seconds\": " << wall_seconds << ",\n"
      << "  \"frame_ms\": {\"p50\": " << percentile_ms(50) << ", \"p99\": " << percentile_ms(99)
      << ", \"max\": " << max_ms() << "},\n"
      << "  \"stage_mean_ms\": {\"voxelize\": " << sum_.voxelize_ms / n
      << ", \"register\": " << sum_.register_ms / n
      << ", \"map_update\": " << sum_.map_update_ms / n << ", \"deskew\": " << sum_.deskew_ms / n
      << "},\n"
      << "  \"deskewed_frames\": " << deskewed_ << ",\n"
      << "  \"mean_distributions_per_scan\": " << distributions_ / n << ",\n"
      << "  \"mean_newton_iterations\": " << iterations_ / n << ",\n"
      << "  \"mean_voxelizations\": " << voxelizations_ / n << ",\n"
      << "  \"regrid_stops\": " << regrid_stops_ << ",\n"
      << "  \"recovery_retries\": " << retries_ << ",\n"
      << "  \"recovery_kept\": " << recoveries_ << ",\n"
      << "  \"map_resets\": " << map_resets_ << ",\n"
      << "  \"mean_self_hits_dropped\": " << self_hits_ / n << ",\n"
      << "  \"keyframes\": " << keyframes_ << ",\n"
      << "  \"registration_failures\": " << failures_ << ",\n"
      << "  \"peak_memory_mib\": " << peak_memory_mib() << ",\n"
      << "  \"skipped_frames\": [";
  for (std::size_t k = 0; k < skipped_.size(); ++k) {
    out << (k ? ", " : "") << "{\"frame\": " << skipped_[k].index
        << ", \"file\": " << json_string(skipped_[k].path)
        << ", \"error\": " << json_string(skipped_[k].error) << "}";
  }
  out << "]";
  if (accuracy) {
    auto number = [](double v) { return std::isfinite(v) ? std::to_string(v) : "null"; };
    out << ",\n  \"accuracy\": {\"kitti_translation_percent\": "
        << number(accuracy->translation_percent)
        << ", \"kitti_rotation_deg_per_100m\": " << number(accuracy->rotation_deg_per_100m)
        << ", \"kitti_segments\": " << accuracy->segments
        << ", \"ate_translation_m\": " << number(accuracy->ate_translation_m)
        << ", \"ate_rotation_deg\": " << number(accuracy->ate_rotation_deg) << "}";
  }
  out << "\n}\n";
  return out.str();
}

double peak_memory_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace litamin2::tools
