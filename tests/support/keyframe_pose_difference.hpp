#pragma once
/// How far two mappers' keyframe poses (Mapper::poses(), same keyframes in the same order) are
/// apart: the largest distance between the positions of a keyframe, metres, over the keyframes
/// both lists hold.

#include "litamin2/mapping/mapper.hpp"

#include <algorithm>
#include <vector>

namespace litamin2::testing {

inline double largest_translation_difference(const std::vector<mapping::KeyframePose>& a,
                                             const std::vector<mapping::KeyframePose>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
    worst = std::max(worst, (a[i].pose.translation() - b[i].pose.translation()).norm());
  return worst;
}

}  // namespace litamin2::testing
