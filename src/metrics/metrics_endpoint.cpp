#include "litamin2/metrics/metrics_endpoint.hpp"

#include <spdlog/spdlog.h>

#include <exception>

namespace litamin2::metrics {

MetricsEndpoint::MetricsEndpoint(const service::MetricsConfig& config, Clock::duration refresh)
    : refresh_(refresh) {
  if (config.enabled()) server_ = std::make_unique<MetricsServer>(config, board_);
}

void MetricsEndpoint::turn(Clock::time_point now, const std::function<std::string()>& render) {
  if (!server_) return;
  board_.beat(now);
  if (now < next_) return;
  board_.publish(render());
  next_ = now + refresh_;
}

void MetricsEndpoint::refresh(const std::function<std::string()>& render) {
  if (!server_) return;
  board_.publish(render());
  next_ = Clock::now() + refresh_;
}

std::unique_ptr<MetricsEndpoint> start_metrics_endpoint(const service::MetricsConfig& config) {
  try {
    auto endpoint = std::make_unique<MetricsEndpoint>(config);
    if (endpoint->enabled())
      spdlog::info("metrics: http://{}/metrics, /healthz, /readyz", config.listen);
    return endpoint;
  } catch (const std::exception& e) {
    spdlog::error("cannot start the metrics endpoint: {}", e.what());
    spdlog::default_logger()->flush();
    return nullptr;
  }
}

}  // namespace litamin2::metrics
