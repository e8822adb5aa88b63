// SIGTERM, SIGINT and SIGHUP are blocked and collected synchronously by ServiceSignals.

#include "litamin2/service/service_signals.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>

using namespace litamin2::service;
using namespace std::chrono_literals;

TEST(ServiceSignals, TimesOutWithoutSignal) {
  ServiceSignals signals;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(signals.wait_for(50ms), 0);
  EXPECT_GE(std::chrono::steady_clock::now() - start, 40ms);
}

TEST(ServiceSignals, CollectsSighupForReload) {
  ServiceSignals signals;
  ASSERT_EQ(::pthread_kill(::pthread_self(), SIGHUP), 0);  // would end the process if unblocked
  EXPECT_EQ(signals.wait_for(1000ms), SIGHUP);
  EXPECT_EQ(signals.wait_for(0ms), 0);
}

TEST(ServiceSignals, CollectsSigtermAndSigint) {
  ServiceSignals signals;
  // Directed at this thread so that no other (unblocked) thread of the test can take it.
  ASSERT_EQ(::pthread_kill(::pthread_self(), SIGTERM), 0);
  EXPECT_EQ(signals.wait_for(1000ms), SIGTERM);
  ASSERT_EQ(::pthread_kill(::pthread_self(), SIGINT), 0);
  EXPECT_EQ(signals.wait_for(1000ms), SIGINT);
  EXPECT_EQ(signals.wait_for(0ms), 0);
}
