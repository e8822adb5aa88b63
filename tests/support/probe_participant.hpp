#pragma once
// The DDS participant of an integration-test probe (tests/integration/*_probe/): the transport
// of a --profile text ("loopback", "shm", "default" or an XML file) on a --domain, with
// DDS-Security when given a --pki folder (scripts/litamin2-pki) and an --identity in it.

#include "litamin2/dds/participant_factory.hpp"

#include <cstdint>
#include <cstdio>
#include <string>

namespace litamin2::testing {

/// The participant named `name`, or nullptr after printing "probe: <why>" to stderr.
inline litamin2::dds::ParticipantPtr probe_participant(const std::string& profile, int domain,
                                                       const std::string& name,
                                                       const std::string& pki = "",
                                                       const std::string& identity = "") {
  std::string error;
  auto pc = litamin2::dds::parse_participant_profile(profile, &error);
  if (pc) {
    pc->domain_id = static_cast<std::uint32_t>(domain);
    pc->name = name;
    if (!pki.empty()) pc->security = litamin2::service::pki_identity(pki, identity);
    if (auto participant = litamin2::dds::create_participant(*pc, &error)) return participant;
  }
  std::fprintf(stderr, "probe: %s\n", error.c_str());
  return nullptr;
}

}  // namespace litamin2::testing
