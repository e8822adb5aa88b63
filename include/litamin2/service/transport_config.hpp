#pragma once
/// How a process joins the DDS domain: the `dds:` section of litamin2d.yaml and
/// litamin2-aggregator.yaml (DESIGN.md section 4). Plain data; dds::participant_config() turns
/// it into a Fast DDS participant.

#include <string>

namespace litamin2::service {

/// Transport setup of a participant.
enum class TransportProfile {
  /// Traffic stays on this host: no builtin transports; UDPv4 bound to 127.0.0.1 (interface
  /// whitelist) with large socket buffers; shared memory with a large segment; discovery by
  /// unicast to the initial peer 127.0.0.1 (no multicast locators at all). The default.
  kLoopback,
  /// Shared memory with a large segment plus UDPv4 on all interfaces with large buffers (in
  /// place of the builtin pair), default multicast discovery: for hosts that talk to other hosts.
  kShm,
  /// Fast DDS's builtin transports and discovery, untouched (SHM segment 512 KiB: slow for
  /// large scans, see DESIGN.md section 4).
  kDefault,
  /// A participant profile from a Fast DDS XML file (TransportConfig::xml_file/xml_profile).
  kXml,
};

/// The name used in configs and on command lines: "loopback", "shm", "default", "xml".
const char* to_string(TransportProfile profile);

struct TransportConfig {
  /// DDS domain id (0..232 for the standard port mapping).
  int domain = 0;
  TransportProfile profile = TransportProfile::kLoopback;
  /// For TransportProfile::kXml: the XML profiles file and the participant profile in it.
  std::string xml_file;
  std::string xml_profile;
};

}  // namespace litamin2::service
