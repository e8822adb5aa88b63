#pragma once
/// What a service's main loop holds for its Prometheus endpoint: the MetricsBoard and, when
/// metrics.listen is set, the MetricsServer on it. The loop calls turn() at every turn (the
/// /healthz heartbeat; the /metrics text re-rendered at most every `refresh`) and set_ready()
/// when its DDS side (and store) are up. Without metrics.listen it does nothing.

#include "litamin2/metrics/metrics_server.hpp"
#include "litamin2/service/metrics_board.hpp"
#include "litamin2/service/metrics_config.hpp"

#include <chrono>
#include <functional>
#include <memory>
#include <string>

namespace litamin2::metrics {

class MetricsEndpoint {
 public:
  using Clock = std::chrono::steady_clock;

  /// Starts the server (std::runtime_error if it cannot bind) when `config` is enabled.
  explicit MetricsEndpoint(const service::MetricsConfig& config,
                           Clock::duration refresh = std::chrono::seconds(1));

  bool enabled() const { return server_ != nullptr; }
  /// The main loop turned at `now`; `render` gives the /metrics text (called only when due).
  void turn(Clock::time_point now, const std::function<std::string()>& render);
  /// Renders now, whatever the time (the first text, the last before stopping).
  void refresh(const std::function<std::string()>& render);
  void set_ready(bool ready) { board_.set_ready(ready); }

 private:
  service::MetricsBoard board_;
  std::unique_ptr<MetricsServer> server_;
  Clock::duration refresh_;
  Clock::time_point next_{};
};

/// A service's endpoint for `config`, started before its DDS side: logs the URLs when enabled;
/// when the port cannot be bound, logs why (flushed) and returns null, and the process exits 1
/// with nothing published.
std::unique_ptr<MetricsEndpoint> start_metrics_endpoint(const service::MetricsConfig& config);

}  // namespace litamin2::metrics
