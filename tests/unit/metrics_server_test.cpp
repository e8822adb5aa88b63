#include "litamin2/metrics/metrics_server.hpp"
#include "litamin2/metrics/metrics_endpoint.hpp"
#include "litamin2/service/prometheus_text.hpp"

#include <gtest/gtest.h>
#include <httplib.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

namespace litamin2::metrics {
namespace {

using Clock = std::chrono::steady_clock;

/// A port of this process (tests of several processes at once do not collide), loopback only.
int test_port(int offset) {
  return 20000 + (static_cast<int>(getpid()) % 20000) + offset;
}

service::MetricsConfig on(int port) {
  return {"127.0.0.1:" + std::to_string(port)};
}

TEST(MetricsServer, ServesTheBoard) {
  service::MetricsBoard board;
  const int port = test_port(0);
  MetricsServer server(on(port), board, std::chrono::milliseconds(500));
  httplib::Client client("127.0.0.1", port);

  auto r = client.Get("/healthz");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);  // starting: the main loop has not begun (store recovery, ...)
  r = client.Get("/readyz");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503);

  board.beat(Clock::now());
  board.set_ready(true);
  board.publish("# HELP a b\n# TYPE a gauge\na 1\n");
  r = client.Get("/healthz");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  r = client.Get("/readyz");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  r = client.Get("/metrics");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, board.text());
  EXPECT_EQ(r->get_header_value("Content-Type"), service::kPrometheusContentType);
  r = client.Get("/other");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);

  // A main loop that stops turning: /healthz goes to 503 after `stale_after`.
  board.beat(Clock::now() - std::chrono::seconds(2));
  r = client.Get("/healthz");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503);
}

TEST(MetricsServer, APortInUseIsAStartError) {
  service::MetricsBoard board;
  const int port = test_port(1);
  MetricsServer first(on(port), board);
  try {
    MetricsServer second(on(port), board);
    FAIL() << "a second server bound the same port";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot listen on 127.0.0.1:" + std::to_string(port)),
              std::string::npos)
        << e.what();
  }
}

TEST(MetricsServer, StopsWhenDestroyedAtOnce) {
  service::MetricsBoard board;
  const auto start = Clock::now();
  { MetricsServer server(on(test_port(2)), board); }
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(2));
}

TEST(MetricsEndpoint, RendersOnlyWhenDueAndNothingWhenOff) {
  int renders = 0;
  auto render = [&] { return "# TYPE r gauge\nr " + std::to_string(++renders) + "\n"; };
  MetricsEndpoint off(service::MetricsConfig{});
  EXPECT_FALSE(off.enabled());
  off.turn(Clock::now(), render);
  EXPECT_EQ(renders, 0);

  MetricsEndpoint endpoint(on(test_port(3)), std::chrono::seconds(1));
  ASSERT_TRUE(endpoint.enabled());
  const auto t0 = Clock::now();
  endpoint.turn(t0, render);
  endpoint.turn(t0 + std::chrono::milliseconds(500), render);
  EXPECT_EQ(renders, 1);
  endpoint.turn(t0 + std::chrono::milliseconds(1100), render);
  EXPECT_EQ(renders, 2);
  httplib::Client client("127.0.0.1", test_port(3));
  const auto r = client.Get("/metrics");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->body, "# TYPE r gauge\nr 2\n");
}

}  // namespace
}  // namespace litamin2::metrics
