#include "litamin2/metrics/metrics_endpoint.hpp"

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

}  // namespace litamin2::metrics
