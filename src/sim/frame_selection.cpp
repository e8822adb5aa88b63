#include "litamin2/sim/frame_selection.hpp"

#include <stdexcept>
#include <string>

#include "litamin2/sim/random.hpp"

namespace litamin2::sim {

void FrameDropOptions::validate() const {
  if (!(probability >= 0.0 && probability < 1.0)) {
    throw std::invalid_argument("frame drop probability " + std::to_string(probability) +
                                " must be in [0, 1)");
  }
  if (max_gap < 1) throw std::invalid_argument("frame drop max_gap must be at least 1");
  if (!(burst_probability >= 0.0 && burst_probability < 1.0)) {
    throw std::invalid_argument("frame drop burst probability " +
                                std::to_string(burst_probability) + " must be in [0, 1)");
  }
  if (burst_min < 1 || burst_max < burst_min) {
    throw std::invalid_argument("frame drop burst length " + std::to_string(burst_min) + ":" +
                                std::to_string(burst_max) +
                                " must be MIN:MAX with 1 <= MIN <= MAX");
  }
}

std::vector<std::size_t> select_frames(std::size_t count, const FrameDropOptions& options,
                                       std::uint64_t seed) {
  options.validate();
  std::vector<std::size_t> kept;
  if (count == 0) return kept;
  kept.push_back(0);
  std::size_t gap = 0;
  std::size_t burst_left = 0;
  for (std::size_t i = 1; i < count; ++i) {
    if (burst_left > 0) {
      --burst_left;
      if (burst_left == 0) {
        gap = 0;
        kept.push_back(i);  // the frame after a burst
      }
      continue;
    }
    if (options.burst_probability > 0.0) {
      Rng burst(hash_combine(hash_combine(seed, 0xb025), i));
      if (burst.chance(options.burst_probability)) {
        // frames i .. i + length - 1 dropped
        burst_left = static_cast<std::size_t>(burst.uniform_int(
            static_cast<int>(options.burst_min), static_cast<int>(options.burst_max)));
        continue;
      }
    }
    Rng rng(hash_combine(hash_combine(seed, 0xd209), i));
    if (gap < options.max_gap && rng.chance(options.probability)) {
      ++gap;
      continue;
    }
    gap = 0;
    kept.push_back(i);
  }
  return kept;
}

}  // namespace litamin2::sim
