#pragma once
// Timing and memory statistics of an odometry run, written as stats.json.

#include "litamin2/core/tracker.hpp"

#include <optional>
#include <string>
#include <vector>

namespace litamin2::tools {

struct Accuracy {
  double translation_percent = 0.0;
  double rotation_deg_per_100m = 0.0;
  std::size_t segments = 0;
  double ate_translation_m = 0.0;
  double ate_rotation_deg = 0.0;
};

class RunStats {
 public:
  void add(const FrameResult& frame);
  /// Frame `index` (file `path`) could not be read and was skipped (--skip-bad-frames).
  void add_skipped(std::size_t index, const std::string& path, const std::string& error);
  std::size_t frames() const { return total_ms_.size(); }
  /// Frames per second of processing time (scan loading excluded).
  double frames_per_second() const;
  double percentile_ms(double p) const;
  double max_ms() const;
  std::size_t keyframes() const { return keyframes_; }
  std::size_t failures() const { return failures_; }
  std::size_t skipped() const { return skipped_.size(); }
  std::size_t deskewed() const { return deskewed_; }

  /// The stats.json document.
  std::string to_json(const std::string& mode, const std::string& sensor, double voxel_size,
                      int threads, double wall_seconds,
                      const std::optional<Accuracy>& accuracy) const;

 private:
  std::vector<double> total_ms_;
  StageTimes sum_;
  std::size_t keyframes_ = 0;
  std::size_t failures_ = 0;
  std::size_t distributions_ = 0;
  std::size_t iterations_ = 0;
  std::size_t voxelizations_ = 0;
  std::size_t regrid_stops_ = 0;
  std::size_t retries_ = 0;
  std::size_t recoveries_ = 0;
  std::size_t retry_registrations_ = 0;
  std::size_t map_resets_ = 0;
  std::size_t pose_searches_ = 0;
  std::size_t poses_found_ = 0;
  std::size_t self_hits_ = 0;
  std::size_t deskewed_ = 0;
  struct Skipped {
    std::size_t index;
    std::string path, error;
  };
  std::vector<Skipped> skipped_;
};

/// Peak resident memory of this process, MiB.
double peak_memory_mib();

}  // namespace litamin2::tools
