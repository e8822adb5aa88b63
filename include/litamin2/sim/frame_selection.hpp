#pragma once
/// Dropped frames and irregular frame spacing: which frames of a trajectory a simulated
/// recording keeps. Real logs lose frames (driver overruns, subsampled recordings), so the
/// motion between consecutive files varies by whole frame periods.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace litamin2::sim {

/// How frames are dropped.
struct FrameDropOptions {
  /// Probability that each frame after the first is dropped (independently, from the seed).
  double probability = 0.0;
  /// Longest run of consecutive dropped frames; the next frame is then kept.
  std::size_t max_gap = 3;

  /// Throws std::invalid_argument unless probability is in [0, 1) and max_gap >= 1.
  void validate() const;
};

/// Indices (increasing, the first always 0) of the frames of `count` that are kept. The same
/// (count, options, seed) gives the same selection; probability 0 keeps every frame.
std::vector<std::size_t> select_frames(std::size_t count, const FrameDropOptions& options,
                                       std::uint64_t seed);

}  // namespace litamin2::sim
