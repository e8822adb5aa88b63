#pragma once
/// Creation of Fast DDS DomainParticipants with the project's transport profiles
/// (DESIGN.md section 4), and forwarding of Fast DDS's log to spdlog.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "litamin2/service/security_config.hpp"
#include "litamin2/service/transport_config.hpp"

#include <fastdds/dds/core/status/StatusMask.hpp>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

namespace litamin2::dds {

using service::TransportProfile;

/// Everything needed to create a participant.
struct ParticipantConfig {
  /// DDS domain id (0..232 for the standard port mapping).
  std::uint32_t domain_id = 0;
  TransportProfile transport = TransportProfile::kLoopback;
  /// Participant name shown in discovery tools.
  std::string name = "litamin2";
  /// kXml: the XML profiles file and the participant profile's name in it.
  std::string xml_file;
  std::string xml_profile = std::string(kDefaultXmlProfile);
  /// kLoopback/kShm: shared-memory segment size (DESIGN.md: 32 MiB gives ~1 ms for 2 MB scans).
  std::uint32_t shm_segment_bytes = 32u << 20;
  /// kLoopback: UDP socket send and receive buffer sizes (the kernel caps them at
  /// net.core.wmem_max / rmem_max).
  std::uint32_t socket_buffer_bytes = 4u << 20;
  /// kLoopback: the host whose unicast locators are used for discovery and data.
  std::string loopback_address = "127.0.0.1";
  /// DDS-Security (any transport profile; with kXml added to the profile's QoS).
  service::SecurityConfig security;
  /// The participant's USER_DATA QoS (any transport profile; with kXml it replaces the
  /// profile's), seen by every other participant in discovery: litamin2d puts its member id
  /// there (daemon/membership.hpp). Empty: none.
  std::string user_data;

  /// Participant profile name used in the shipped XML files (config/dds/*.xml).
  static constexpr std::string_view kDefaultXmlProfile = "litamin2";
};

/// Parses a command-line/config profile: "loopback", "shm", "default", or the path of an XML
/// file ending in ".xml", optionally followed by ":PROFILE" (default profile name "litamin2").
/// Other fields of the result keep their defaults. Returns std::nullopt and sets *error on an
/// unknown name.
std::optional<ParticipantConfig> parse_participant_profile(std::string_view text,
                                                           std::string* error = nullptr);

/// The participant QoS of a config, with its security properties (not for kXml, whose QoS
/// comes from the file: for kXml this returns the factory's default QoS with the name set).
eprosima::fastdds::dds::DomainParticipantQos participant_qos(const ParticipantConfig& config);

/// Deletes a participant's contained entities, then the participant.
struct ParticipantDeleter {
  void operator()(eprosima::fastdds::dds::DomainParticipant* participant) const;
};
using ParticipantPtr =
    std::unique_ptr<eprosima::fastdds::dds::DomainParticipant, ParticipantDeleter>;

/// Creates a participant (installing the spdlog log forwarding first, see
/// forward_fastdds_log_to_spdlog). Returns nullptr and sets *error (if given) when the XML file
/// cannot be loaded, the profile does not exist, the security files do not pass
/// security_files_error, Fast DDS refuses the QoS, or the test-only variable
/// LITAMIN2_TEST_UDP_LOSS_PERCENT is invalid. When that variable is set (tests only), the
/// participant's UDPv4 transports are made lossy and its shared memory removed, with a warning
/// (test_udp_loss.hpp).
ParticipantPtr create_participant(
    const ParticipantConfig& config, std::string* error = nullptr,
    eprosima::fastdds::dds::DomainParticipantListener* listener = nullptr,
    const eprosima::fastdds::dds::StatusMask& mask = eprosima::fastdds::dds::StatusMask::none());

/// Replaces Fast DDS's console log consumers by one forwarding every entry to spdlog's default
/// logger (Error -> error, Warning -> warn, Info -> debug; logger name "fastdds" in the
/// message), and sets Fast DDS's verbosity to Warning. Registers stop_fastdds_log with
/// std::atexit, so that it runs before spdlog's registry is destroyed in every process and test
/// that forwards. Idempotent and thread-safe; does nothing after stop_fastdds_log.
void forward_fastdds_log_to_spdlog();

/// Delivers the queued Fast DDS log entries to spdlog, then detaches spdlog (later entries go to
/// stderr) and stops Fast DDS's log thread: Fast DDS's log thread must never deliver to spdlog
/// once static destruction has begun. Mains call it before returning; it also runs at exit.
/// Idempotent and thread-safe.
void stop_fastdds_log();

}  // namespace litamin2::dds
