#pragma once
// The DDS participant of an integration-test probe (tests/integration/*_probe/, raw_cdr_writer):
// the transport of a --profile text ("loopback", "shm", "default" or an XML file) on a --domain,
// with DDS-Security when given a --pki folder (scripts/litamin2-pki) and an --identity in it.

#include "litamin2/dds/participant_factory.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <string>

namespace litamin2::testing {

/// The command-line options that choose a probe's participant.
struct ProbeParticipantOptions {
  std::string profile = "loopback";
  int domain = 0;
  std::string pki;
  std::string identity;

  /// --domain, --profile, --pki and --identity on `app`.
  void add_to(CLI::App& app) {
    app.add_option("--domain", domain);
    app.add_option("--profile", profile);
    app.add_option("--pki", pki, "DDS-Security: a scripts/litamin2-pki folder");
    app.add_option("--identity", identity, "DDS-Security: the identity in --pki");
  }
};

/// The participant named `name`, or nullptr after printing "probe: <why>" to stderr.
inline litamin2::dds::ParticipantPtr probe_participant(const ProbeParticipantOptions& options,
                                                       const std::string& name) {
  std::string error;
  auto pc = litamin2::dds::parse_participant_profile(options.profile, &error);
  if (pc) {
    pc->domain_id = static_cast<std::uint32_t>(options.domain);
    pc->name = name;
    if (!options.pki.empty())
      pc->security = litamin2::service::pki_identity(options.pki, options.identity);
    if (auto participant = litamin2::dds::create_participant(*pc, &error)) return participant;
  }
  std::fprintf(stderr, "probe: %s\n", error.c_str());
  return nullptr;
}

}  // namespace litamin2::testing
