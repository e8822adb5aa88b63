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
  /// Bursts: probability that a burst of dropped frames starts at each frame after the first
  /// (independently of the single drops above). A burst drops burst_min..burst_max consecutive
  /// frames (uniform, from the seed), so that the motion between two files can be many frames'
  /// worth: the breaks of the real VLP-16 drive (5-16 m, turns of tens of degrees;
  /// docs/accuracy.md "Breaks in the real VLP-16 drive"). 0: no bursts.
  double burst_probability = 0.0;
  std::size_t burst_min = 5;
  std::size_t burst_max = 15;

  /// Throws std::invalid_argument unless probability and burst_probability are in [0, 1),
  /// max_gap >= 1 and 1 <= burst_min <= burst_max.
  void validate() const;
};

/// Indices (increasing, the first always 0) of the frames of `count` that are kept. The same
/// (count, options, seed) gives the same selection; probability 0 and burst_probability 0 keep
/// every frame. The frame after a burst is always kept.
std::vector<std::size_t> select_frames(std::size_t count, const FrameDropOptions& options,
                                       std::uint64_t seed);

}  // namespace litamin2::sim
