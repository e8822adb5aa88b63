#include "odometry/run_stats.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <nlohmann/json.hpp>

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
  retry_registrations_ += static_cast<std::size_t>(frame.retry_registrations);
  map_resets_ += frame.map_reset ? 1 : 0;
  pose_searches_ += frame.pose_searched ? 1 : 0;
  poses_found_ += frame.pose_found ? 1 : 0;
  self_hits_ += static_cast<std::size_t>(frame.self_hits);
}

void RunStats::add_skipped(std::size_t index, const std::string& path, const std::string& error) {
  skipped_.push_back({index, path, error});
}

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
  using Json = nlohmann::ordered_json;
  // A JSON number, or null for an undefined figure (NaN/Inf are not JSON).
  const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(); };
  const double n = std::max<double>(1.0, static_cast<double>(frames()));
  Json skipped = Json::array();
  for (const Skipped& s : skipped_)
    skipped.push_back({{"frame", s.index}, {"file", s.path}, {"error", s.error}});
  Json stats = {{"frames", frames()},
                {"mode", mode},
                {"sensor", sensor},
                {"voxel_size", voxel_size},
                {"threads", threads},
                {"frames_per_second", number(frames_per_second())},
                {"wall_seconds", number(wall_seconds)},
                {"frame_ms",
                 {{"p50", number(percentile_ms(50))},
                  {"p99", number(percentile_ms(99))},
                  {"max", number(max_ms())}}},
                {"stage_mean_ms",
                 {{"voxelize", sum_.voxelize_ms / n},
                  {"register", sum_.register_ms / n},
                  {"map_update", sum_.map_update_ms / n},
                  {"deskew", sum_.deskew_ms / n}}},
                {"deskewed_frames", deskewed_},
                {"mean_distributions_per_scan", distributions_ / n},
                {"mean_newton_iterations", iterations_ / n},
                {"mean_voxelizations", voxelizations_ / n},
                {"regrid_stops", regrid_stops_},
                {"recovery_retries", retries_},
                {"recovery_kept", recoveries_},
                {"recovery_registrations", retry_registrations_},
                {"map_resets", map_resets_},
                {"global_searches", pose_searches_},
                {"global_search_kept", poses_found_},
                {"mean_self_hits_dropped", self_hits_ / n},
                {"keyframes", keyframes_},
                {"registration_failures", failures_},
                {"peak_memory_mib", peak_memory_mib()},
                {"skipped_frames", skipped}};
  if (accuracy) {
    stats["accuracy"] = {{"kitti_translation_percent", number(accuracy->translation_percent)},
                         {"kitti_rotation_deg_per_100m", number(accuracy->rotation_deg_per_100m)},
                         {"kitti_segments", accuracy->segments},
                         {"ate_translation_m", number(accuracy->ate_translation_m)},
                         {"ate_rotation_deg", number(accuracy->ate_rotation_deg)}};
  }
  // Invalid UTF-8 in a skipped file's name is replaced, not thrown (the stats are still written).
  return stats.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

double peak_memory_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace litamin2::tools
