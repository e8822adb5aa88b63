#include "link_emulator/link_profile.hpp"

#include <cmath>

namespace litamin2::testing {

std::string validate(const LinkProfile& profile) {
  if (profile.delay.count() < 0) return "delay must be >= 0";
  if (profile.jitter.count() < 0) return "jitter must be >= 0";
  if (profile.jitter > profile.delay) return "jitter must not exceed the delay";
  if (!(profile.loss_fraction >= 0.0 && profile.loss_fraction <= 1.0))
    return "loss must be within 0..100 %";
  if (profile.queue_limit_frames == 0) return "queue limit must be >= 1 frame";
  return {};
}

}  // namespace litamin2::testing
