// SIGTERM/SIGINT are blocked and collected synchronously by ShutdownSignals.

#include "litamin2/service/shutdown_signals.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>

using namespace litamin2::service;
using namespace std::chrono_literals;

TEST(ShutdownSignals, TimesOutWithoutSignal) {
  ShutdownSignals signals;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(signals.wait_for(50ms), 0);
  EXPECT_GE(std::chrono::steady_clock::now() - start, 40ms);
}

TEST(ShutdownSignals, CollectsSigtermAndSigint) {
  ShutdownSignals signals;
  // Directed at this thread so that no other (unblocked) thread of the test can take it.
  ASSERT_EQ(::pthread_kill(::pthread_self(), SIGTERM), 0);
  EXPECT_EQ(signals.wait_for(1000ms), SIGTERM);
  ASSERT_EQ(::pthread_kill(::pthread_self(), SIGINT), 0);
  EXPECT_EQ(signals.wait_for(1000ms), SIGINT);
  EXPECT_EQ(signals.wait_for(0ms), 0);
}
