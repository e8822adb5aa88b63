// link_emulator: a test-only userspace link between two TAP devices, for kernels without
// sch_netem (tests/integration/multihost.sh, scenario delay). It creates TAP device A and B
// (each optionally in another network namespace, --netns-a/--netns-b), and forwards every
// Ethernet frame read from one to the other after --delay-ms (+- --jitter-ms, uniform; a
// jitter larger than the gap between frames reorders them), dropping --loss-percent of them
// at random and any beyond --queue-frames in flight per direction. The devices are not
// configured here (addresses, bridge, up: `ip link`), and vanish when it exits.
// SIGTERM or SIGINT: exits 0 after printing each direction's counters (frames still in flight
// are dropped and counted as queued at exit). Exit 2 on invalid options, 1 on a system error.

#include "link_emulator/delay_line.hpp"
#include "link_emulator/link_profile.hpp"
#include "link_emulator/tap_device.hpp"

#include <poll.h>
#include <signal.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>

using litamin2::testing::DelayLine;
using litamin2::testing::LinkProfile;
using litamin2::testing::TapDevice;

namespace {

volatile sig_atomic_t stop_requested = 0;
void request_stop(int) {
  stop_requested = 1;
}

// One direction: frames read from `from` wait in `line`, then are written to `to`.
struct Direction {
  const TapDevice& from;
  const TapDevice& to;
  DelayLine line;
  std::uint64_t write_errors = 0;  // write(2) to `to` failed (device down, no buffer)
  std::uint64_t read_errors = 0;   // read(2) from `from` failed other than EAGAIN
};

// Reads what `from` has (at most a batch, so that the other direction gets its turn).
void read_frames(Direction& d, std::array<std::uint8_t, 65536>& buffer) {
  for (int i = 0; i < 256; ++i) {
    const ssize_t n = ::read(d.from.fd(), buffer.data(), buffer.size());
    if (n < 0) {
      if (errno != EAGAIN && errno != EINTR) ++d.read_errors;
      return;
    }
    d.line.push(DelayLine::Frame(buffer.begin(), buffer.begin() + n), DelayLine::Clock::now());
  }
}

void write_due(Direction& d) {
  DelayLine::Frame frame;
  while (d.line.pop_due(DelayLine::Clock::now(), frame)) {
    if (::write(d.to.fd(), frame.data(), frame.size()) != static_cast<ssize_t>(frame.size()))
      ++d.write_errors;
  }
}

void print_counters(const Direction& d) {
  const auto& c = d.line.counters();
  std::fprintf(
      stderr,
      "link_emulator: %s -> %s: received %llu forwarded %llu reordered %llu lost %llu "
      "queue_full %llu write_errors %llu read_errors %llu queued_at_exit %zu bytes %llu "
      "max_queued %zu\n",
      d.from.name().c_str(), d.to.name().c_str(), static_cast<unsigned long long>(c.received),
      static_cast<unsigned long long>(c.forwarded), static_cast<unsigned long long>(c.reordered),
      static_cast<unsigned long long>(c.lost),
      static_cast<unsigned long long>(c.dropped_queue_full),
      static_cast<unsigned long long>(d.write_errors),
      static_cast<unsigned long long>(d.read_errors), d.line.queued(),
      static_cast<unsigned long long>(c.bytes_forwarded), c.max_queued);
}

std::chrono::nanoseconds from_ms(double ms) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(ms * 1e6)));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "link_emulator (tests only): forwards Ethernet frames between two TAP devices after a "
      "delay, with optional jitter and loss"};
  std::string tap_a, tap_b, netns_a, netns_b, ready_file;
  double delay_ms = 0.0, jitter_ms = 0.0, loss_percent = 0.0;
  LinkProfile profile;
  app.add_option("--tap-a", tap_a, "name of TAP device A (created here)")->required();
  app.add_option("--netns-a", netns_a, "network namespace of A, e.g. /run/netns/NAME");
  app.add_option("--tap-b", tap_b, "name of TAP device B (created here)")->required();
  app.add_option("--netns-b", netns_b, "network namespace of B");
  app.add_option("--delay-ms", delay_ms, "one-way delay, each direction (ms)");
  app.add_option("--jitter-ms", jitter_ms, "uniform jitter around the delay, <= delay (ms)");
  app.add_option("--loss-percent", loss_percent, "frames dropped at random, each direction");
  app.add_option("--queue-frames", profile.queue_limit_frames,
                 "frames in flight per direction; more are dropped and counted");
  app.add_option("--seed", profile.seed, "seed of the loss and jitter draws");
  app.add_option("--ready-file", ready_file, "written once both devices exist");
  CLI11_PARSE(app, argc, argv);

  profile.delay = from_ms(delay_ms);
  profile.jitter = from_ms(jitter_ms);
  profile.loss_fraction = loss_percent / 100.0;
  if (const std::string error = litamin2::testing::validate(profile); !error.empty()) {
    std::fprintf(stderr, "link_emulator: invalid options: %s\n", error.c_str());
    return 2;
  }
  if (tap_a == tap_b && netns_a == netns_b) {
    std::fprintf(stderr, "link_emulator: invalid options: A and B are the same device\n");
    return 2;
  }

  // SIGTERM/SIGINT are blocked except while waiting in ppoll, so that they end the wait.
  sigset_t blocked, during_wait;
  sigemptyset(&blocked);
  sigaddset(&blocked, SIGTERM);
  sigaddset(&blocked, SIGINT);
  sigprocmask(SIG_BLOCK, &blocked, &during_wait);
  sigdelset(&during_wait, SIGTERM);
  sigdelset(&during_wait, SIGINT);
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);

  try {
    TapDevice a(tap_a, netns_a);
    TapDevice b(tap_b, netns_b);
    Direction a_to_b{a, b, DelayLine(profile)};
    LinkProfile reverse_profile = profile;
    reverse_profile.seed = profile.seed + 1;  // independent draws in each direction
    Direction b_to_a{b, a, DelayLine(reverse_profile)};
    std::fprintf(stderr,
                 "link_emulator: %s <-> %s: delay %.3f ms, jitter %.3f ms, loss %.2f %%, queue "
                 "%zu frames\n",
                 tap_a.c_str(), tap_b.c_str(), delay_ms, jitter_ms, loss_percent,
                 profile.queue_limit_frames);
    if (!ready_file.empty()) std::ofstream(ready_file) << "ready\n";

    std::array<std::uint8_t, 65536> buffer{};
    while (!stop_requested) {
      timespec timeout{1, 0};  // nothing in flight: wake up now and then for the signal flag
      std::optional<DelayLine::Clock::time_point> next;
      for (const Direction* d : {&a_to_b, &b_to_a}) {
        const auto release = d->line.next_release();
        if (release && (!next || *release < *next)) next = release;
      }
      if (next) {
        const auto wait = std::max(std::chrono::nanoseconds(0), *next - DelayLine::Clock::now());
        timeout.tv_sec = static_cast<time_t>(wait.count() / 1'000'000'000);
        timeout.tv_nsec = static_cast<long>(wait.count() % 1'000'000'000);
      }
      std::array<pollfd, 2> fds{pollfd{a.fd(), POLLIN, 0}, pollfd{b.fd(), POLLIN, 0}};
      const int ready = ::ppoll(fds.data(), fds.size(), &timeout, &during_wait);
      if (ready < 0 && errno != EINTR)
        throw std::runtime_error(std::string("ppoll: ") + std::strerror(errno));
      if (ready > 0) {
        if (fds[0].revents & POLLIN) read_frames(a_to_b, buffer);
        if (fds[1].revents & POLLIN) read_frames(b_to_a, buffer);
      }
      write_due(a_to_b);
      write_due(b_to_a);
    }
    print_counters(a_to_b);
    print_counters(b_to_a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "link_emulator: %s\n", e.what());
    return 1;
  }
  return 0;
}
