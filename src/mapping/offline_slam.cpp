#include "litamin2/mapping/offline_slam.hpp"

#include "litamin2/core/stopwatch.hpp"

#include <chrono>

namespace litamin2::mapping {

OfflineSlam::OfflineSlam(const MapperConfig& config) : mapper_(config) {}

void OfflineSlam::add(const Tracker& tracker, const FrameResult& frame, Stamp stamp) {
  if (frame.keyframe) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<LoopEdge> loops;
    frame_of_keyframe_.push_back(keyframe_of_frame_.size());
    mapper_.add_keyframe(make_keyframe(tracker, frame, KeyframeKey{kStream, next_id_}, stamp),
                         &loops);
    if (!loops.empty()) mapper_.optimize();
    ++next_id_;
    milliseconds_ += elapsed_ms(start);
  }
  keyframe_of_frame_.push_back(next_id_ == 0 ? 0 : next_id_ - 1);
}

std::vector<Eigen::Isometry3d> OfflineSlam::corrected(
    const std::vector<Eigen::Isometry3d>& odometry) {
  // The local optimisations ran as loops were found; one full pass settles the whole graph.
  if (mapper_.loops_since_full_pass() > 0) mapper_.optimize_full();
  std::vector<Eigen::Isometry3d> out;
  out.reserve(odometry.size());
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    const auto c = mapper_.correction(kStream, keyframe_of_frame_[i]);
    out.push_back(c ? c->pose * odometry[i] : odometry[i]);
  }
  return out;
}

std::vector<OfflineSlam::Loop> OfflineSlam::loops() const {
  std::vector<Loop> out;
  for (const LoopEdge& loop : mapper_.loops())
    out.push_back({frame_of_keyframe_[loop.from.id], frame_of_keyframe_[loop.to.id], loop.fitness,
                   loop.rmse});
  return out;
}

}  // namespace litamin2::mapping
