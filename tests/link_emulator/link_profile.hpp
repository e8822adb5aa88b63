// What the test link emulator does to each frame it forwards, in each direction: a fixed
// one-way delay, a uniform jitter around it, random loss and a bound on the frames in flight.
// Test-only (tests/link_emulator/): it stands in for `tc qdisc ... netem delay 100ms loss 10%`
// on kernels without sch_netem.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

namespace litamin2::testing {

struct LinkProfile {
  std::chrono::nanoseconds delay{0};   // one way, each direction
  std::chrono::nanoseconds jitter{0};  // release time uniform in [delay - jitter, delay + jitter]
  double loss_fraction = 0.0;          // each frame dropped with this probability, 0..1
  std::size_t queue_limit_frames = 4096;  // frames in flight per direction; more are dropped
  std::uint64_t seed = 1;                 // of the loss and jitter draws
};

// Empty when the profile is valid, else what is wrong with it. Rejected: a negative delay or
// jitter, a jitter larger than the delay (a frame would be released before it arrived), a loss
// fraction outside 0..1 (or NaN), a queue limit of 0.
std::string validate(const LinkProfile& profile);

}  // namespace litamin2::testing
