#include "litamin2/service/security_config.hpp"

#include <fstream>

namespace litamin2::service {

SecurityConfig pki_identity(const std::string& dir, const std::string& name) {
  SecurityConfig c;
  c.enabled = true;
  c.identity_ca = dir + "/ca/identity_ca.pem";
  c.certificate = dir + "/" + name + "/cert.pem";
  c.private_key = dir + "/" + name + "/key.pem";
  c.permissions_ca = dir + "/ca/permissions_ca.pem";
  c.governance = dir + "/governance.p7s";
  c.permissions = dir + "/" + name + "/permissions.p7s";
  return c;
}

std::optional<std::string> security_config_error(const SecurityConfig& config) {
  if (!config.enabled) return std::nullopt;
  for (const auto& [key, member] : SecurityConfig::kFiles) {
    const std::string name = std::string("security.") + key;
    const std::string& path = config.*member;
    if (path.empty()) return name + ": required when security.enabled is true";
    if (!std::ifstream(path)) return name + ": cannot open '" + path + "'";
  }
  return std::nullopt;
}

}  // namespace litamin2::service
