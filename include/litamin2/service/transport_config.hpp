#pragma once
/// How a process joins the DDS domain: the `dds:` section of litamin2d.yaml and
/// litamin2-aggregator.yaml (DESIGN.md section 4). Plain data; dds::participant_config() turns
/// it into a Fast DDS participant.

#include <optional>
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

/// Where TransportConfig::domain came from.
enum class DomainSource {
  /// No `dds.domain` key and no ROS_DOMAIN_ID: 0, as ROS 2's default.
  kDefault,
  /// The config's `dds.domain` (it wins over the environment).
  kConfig,
  /// The ROS_DOMAIN_ID environment variable (the config set no domain).
  kEnvironment,
};

/// "default", "config", "ROS_DOMAIN_ID".
const char* to_string(DomainSource source);

/// The domain id in a ROS_DOMAIN_ID value: std::nullopt and no error for null or an empty
/// string (ROS 2 treats an empty value as unset); std::nullopt and `*error` set for anything
/// but a decimal integer in 0..232 (no sign, no spaces, no trailing characters).
std::optional<int> parse_ros_domain_id(const char* value, std::string* error);

struct TransportConfig {
  /// DDS domain id (0..232 for the standard port mapping).
  int domain = 0;
  DomainSource domain_source = DomainSource::kDefault;
  TransportProfile profile = TransportProfile::kLoopback;
  /// For TransportProfile::kXml: the XML profiles file and the participant profile in it.
  std::string xml_file;
  std::string xml_profile;
};

}  // namespace litamin2::service
