#pragma once
/// The `metrics:` section of both processes' configs: where the Prometheus endpoint
/// (/metrics, /healthz, /readyz) listens. Empty `listen`: no endpoint (the default).

#include <optional>
#include <string>

namespace litamin2::service {

struct MetricsConfig {
  /// "host:port" (an IPv4 address, a host name, or "[IPv6]"; port 1..65535), or empty: off.
  std::string listen;
  bool enabled() const { return !listen.empty(); }
};

/// A parsed `listen` value.
struct ListenAddress {
  /// Without the brackets of an IPv6 address.
  std::string host;
  int port = 0;
};

/// `text` as host:port; nullopt with the reason in `*error` if it is not one.
std::optional<ListenAddress> parse_listen_address(const std::string& text, std::string* error);

/// Why `config` is invalid (a message naming metrics.listen), or nullopt.
std::optional<std::string> metrics_config_error(const MetricsConfig& config);

}  // namespace litamin2::service
