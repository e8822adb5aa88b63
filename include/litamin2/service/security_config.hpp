#pragma once
/// The `security:` section of both processes' configs: DDS-Security (PKI-DH authentication,
/// Access-Permissions with signed governance and permissions, AES-GCM encryption) as compiled
/// into Fast DDS. Plain data and its validation; dds::security_files_error checks the files'
/// contents (certificates, signatures, expiry) and dds::participant_qos applies it.
/// docs/security.md; scripts/litamin2-pki makes the files.

#include <optional>
#include <string>
#include <utility>

namespace litamin2::service {

struct SecurityConfig {
  /// Off by default: the demo and a first run need no PKI.
  bool enabled = false;
  /// PEM certificate of the CA that issued every participant's identity certificate.
  std::string identity_ca;
  /// This participant's PEM identity certificate, issued by identity_ca.
  std::string certificate;
  /// Its PEM private key (readable by the service's user only).
  std::string private_key;
  /// PEM certificate of the CA that signed the governance and permissions documents.
  std::string permissions_ca;
  /// The domain governance document, S/MIME-signed by permissions_ca (governance.p7s).
  std::string governance;
  /// This participant's permissions document, S/MIME-signed by permissions_ca, with a grant
  /// for the certificate's subject (permissions.p7s).
  std::string permissions;

  /// The six files by their key in the section, in the order they are checked.
  static constexpr std::pair<const char*, std::string SecurityConfig::*> kFiles[] = {
      {"identity_ca", &SecurityConfig::identity_ca},
      {"certificate", &SecurityConfig::certificate},
      {"private_key", &SecurityConfig::private_key},
      {"permissions_ca", &SecurityConfig::permissions_ca},
      {"governance", &SecurityConfig::governance},
      {"permissions", &SecurityConfig::permissions}};
};

/// The security files of participant `name` in a folder made by scripts/litamin2-pki
/// (ca/identity_ca.pem, ca/permissions_ca.pem, governance.p7s, NAME/{cert,key}.pem,
/// NAME/permissions.p7s), enabled. The tools' and probes' --pki DIR --identity NAME.
SecurityConfig pki_identity(const std::string& dir, const std::string& name);

/// Why the section is invalid ("security.<key>: ..."), or std::nullopt: when security is enabled,
/// each of the six files must be given and readable. (The config reader throws it as a
/// ConfigError.)
std::optional<std::string> security_config_error(const SecurityConfig& config);

}  // namespace litamin2::service
