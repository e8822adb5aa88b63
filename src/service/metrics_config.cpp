#include "litamin2/service/metrics_config.hpp"

#include <cctype>

namespace litamin2::service {

namespace {

bool host_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-' || c == '_';
}

bool ipv6_char(char c) {
  return std::isxdigit(static_cast<unsigned char>(c)) != 0 || c == ':' || c == '.';
}

}  // namespace

std::optional<ListenAddress> parse_listen_address(const std::string& text, std::string* error) {
  auto fail = [&](const std::string& why) -> std::optional<ListenAddress> {
    if (error) *error = why;
    return std::nullopt;
  };
  ListenAddress address;
  std::string port;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string::npos || close + 1 >= text.size() || text[close + 1] != ':')
      return fail("an IPv6 address wants the form [ADDRESS]:PORT");
    address.host = text.substr(1, close - 1);
    port = text.substr(close + 2);
    if (address.host.empty()) return fail("empty IPv6 address");
    for (char c : address.host)
      if (!ipv6_char(c)) return fail("'" + address.host + "' is not an IPv6 address");
  } else {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos) return fail("wants HOST:PORT");
    address.host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (address.host.empty()) return fail("empty host (use 127.0.0.1 or 0.0.0.0)");
    for (char c : address.host)
      if (!host_name_char(c)) return fail("'" + address.host + "' is not a host name or address");
  }
  if (port.empty() || port.size() > 5) return fail("port '" + port + "' is not in 1..65535");
  int value = 0;
  for (char c : port) {
    if (!std::isdigit(static_cast<unsigned char>(c)))
      return fail("port '" + port + "' is not in 1..65535");
    value = value * 10 + (c - '0');
  }
  if (value < 1 || value > 65535) return fail("port '" + port + "' is not in 1..65535");
  address.port = value;
  return address;
}

std::optional<std::string> metrics_config_error(const MetricsConfig& config) {
  if (!config.enabled()) return std::nullopt;
  std::string why;
  if (!parse_listen_address(config.listen, &why))
    return "metrics.listen: '" + config.listen + "': " + why;
  return std::nullopt;
}

}  // namespace litamin2::service
