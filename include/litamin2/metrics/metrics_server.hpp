#pragma once
/// The Prometheus endpoint of litamin2d and litamin2-aggregator, on cpp-httplib (Debian's
/// libcpp-httplib-dev): GET /metrics (the board's text, exposition format 0.0.4), /healthz
/// (200 while starting and while the main loop turns, 503 once it has not for `stale_after`),
/// /readyz (200 while the board says ready, else 503). One server thread that reads only the
/// MetricsBoard: it never takes a lock of the tracking or mapping path. Transport only: what is
/// served is rendered by the process.

#include "litamin2/service/metrics_board.hpp"
#include "litamin2/service/metrics_config.hpp"

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

namespace httplib {
class Server;
}

namespace litamin2::metrics {

class MetricsServer {
 public:
  /// Binds config.listen (must be enabled and valid) and starts serving. Throws
  /// std::runtime_error naming the address if it cannot bind (taken, not local, no rights).
  /// The port is taken exclusively (no SO_REUSEPORT: a second process fails here).
  MetricsServer(const service::MetricsConfig& config, const service::MetricsBoard& board,
                std::chrono::milliseconds stale_after = std::chrono::seconds(5));
  /// Stops serving and joins the thread.
  ~MetricsServer();
  MetricsServer(const MetricsServer&) = delete;
  MetricsServer& operator=(const MetricsServer&) = delete;

  /// The port bound (the configured one).
  int port() const { return port_; }

 private:
  std::unique_ptr<httplib::Server> server_;
  std::thread thread_;
  std::atomic<bool> finished_{false};
  int port_ = 0;
};

}  // namespace litamin2::metrics
