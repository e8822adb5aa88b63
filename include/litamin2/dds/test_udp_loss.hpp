#pragma once
/// TEST ONLY: a lossy UDP link emulated inside one process's DDS participant, for the
/// packet-loss integration test (tests/integration/lossy_link.sh) on machines whose kernel has
/// no sch_netem. Opt-in through the environment variable LITAMIN2_TEST_UDP_LOSS_PERCENT; never
/// set it in a deployment.
///
/// With LITAMIN2_TEST_UDP_LOSS_PERCENT=N (an integer 0..100), every UDPv4 transport of the
/// participant is replaced by Fast DDS's test_UDPv4TransportDescriptor with the same interface
/// whitelist, socket buffers, message size, initial peers range and TTL, dropping N % (at
/// random, independently per message, as a lossy link does) of the DATA, DATA_FRAG, HEARTBEAT
/// and ACKNACK messages it sends; a datagram is dropped when one of its submessages is. Fast
/// DDS drops at send: a lossy participant loses what it sends, not what it receives, so a
/// lossy link between two processes needs the variable in both. Its shared-memory transports are
/// removed, so that no peer on this host bypasses the loss (a participant with no SHM transport can
/// only be reached by UDP). N = 0 gives the same transports with nothing dropped: the baseline for
/// measuring what the loss costs. Delay is not emulated.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

namespace litamin2::dds {

/// The environment variable read by create_participant.
inline constexpr const char* kTestUdpLossEnv = "LITAMIN2_TEST_UDP_LOSS_PERCENT";

/// Parses a drop percentage: a decimal integer 0..100, nothing else (no sign, no spaces, no
/// '%'). Returns std::nullopt and sets *error (naming kTestUdpLossEnv) otherwise.
std::optional<std::uint8_t> parse_test_udp_loss_percent(std::string_view text,
                                                        std::string* error = nullptr);

/// The drop percentage requested by the environment: std::nullopt with *error empty when
/// kTestUdpLossEnv is unset or empty; std::nullopt with *error set when its value is invalid.
std::optional<std::uint8_t> test_udp_loss_from_env(std::string* error);

/// Makes qos's participant lossy (see the file comment). Builtin transports are replaced by
/// one lossy UDPv4 transport with Fast DDS's defaults. Returns false and sets *error when qos
/// has no UDPv4 transport to replace (e.g. only TCP or UDPv6 user transports).
bool apply_test_udp_loss(eprosima::fastdds::dds::DomainParticipantQos& qos, std::uint8_t percent,
                         std::string* error = nullptr);

/// What the lossy transports of this process saw and dropped, per submessage kind: `seen`
/// submessages of that kind inspected (the inspection of a datagram stops at the first
/// dropped submessage), `dropped` datagrams dropped because of one of them.
struct TestUdpLossCounts {
  struct Kind {
    std::uint64_t seen = 0;
    std::uint64_t dropped = 0;
  };
  Kind data, data_frag, heartbeat, acknack;
};
TestUdpLossCounts test_udp_loss_counts();

/// "DATA dropped/seen, DATA_FRAG dropped/seen, HEARTBEAT ..., ACKNACK ...".
std::string to_string(const TestUdpLossCounts& counts);

/// Prints the counts to stderr at exit (std::atexit, once per process), as
/// "TEST ONLY: LITAMIN2_TEST_UDP_LOSS_PERCENT: datagrams dropped/submessages seen: ...".
/// create_participant calls it when kTestUdpLossEnv is set.
void report_test_udp_loss_at_exit();

/// Turns off Fast DDS's intraprocess delivery for the whole process (library settings), which
/// would otherwise carry samples between two participants of one process around every
/// transport, lossy or not. create_participant calls it when kTestUdpLossEnv is set.
void turn_off_intraprocess_delivery();

}  // namespace litamin2::dds
