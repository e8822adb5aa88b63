#pragma once
/// The files of a `security:` section checked before Fast DDS gets them, so that a process stops
/// at start with a message naming the file and what is wrong with it (Fast DDS itself only says
/// "Cannot create participant due to initialization error"). docs/security.md.

#include "litamin2/service/security_config.hpp"

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

#include <optional>
#include <string>

namespace litamin2::dds {

/// Why the security files cannot work for a participant on `domain` (std::nullopt when they
/// can). The message starts with the key ("security.permissions: ...") and names the file. Checks:
///  - identity_ca, certificate, permissions_ca: PEM certificates, valid now (not expired, not
///    before their start);
///  - certificate: issued by identity_ca; private_key: a PEM private key matching it;
///  - governance, permissions: S/MIME documents whose signature verifies against
///    permissions_ca (unsigned, tampered or signed by another CA fail);
///  - permissions: a grant whose subject_name is the certificate's subject (as DDS-Security
///    compares them), valid now, covering `domain`; governance: a domain rule covering it.
std::optional<std::string> security_files_error(const service::SecurityConfig& config, int domain);

/// Adds the DDS-Security properties of `config` (builtin PKI-DH, Access-Permissions and
/// AES-GCM-GMAC plugins, file:// URIs of its files) to a participant QoS. Nothing when disabled.
void add_security_properties(const service::SecurityConfig& config,
                             eprosima::fastdds::dds::DomainParticipantQos& qos);

}  // namespace litamin2::dds
