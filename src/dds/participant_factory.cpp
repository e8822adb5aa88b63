#include "litamin2/dds/participant_factory.hpp"

#include "litamin2/dds/security_files.hpp"
#include "litamin2/dds/test_udp_loss.hpp"

#include <spdlog/spdlog.h>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

namespace litamin2::dds {

namespace fdds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

namespace {

/// Participant ids probed by unicast discovery on the loopback peer (Fast DDS's default is 4):
/// room for the daemons, tools and tests of one host.
constexpr std::uint32_t kLoopbackPeerRange = 32;

std::shared_ptr<eprosima::fastdds::rtps::SharedMemTransportDescriptor> shm_transport(
    std::uint32_t segment_bytes) {
  auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
  shm->segment_size(segment_bytes);
  return shm;
}

rtps::Locator_t udp_locator(const std::string& address) {
  rtps::Locator_t locator;
  locator.kind = LOCATOR_KIND_UDPv4;
  rtps::IPLocator::setIPv4(locator, address);
  locator.port = 0;  // Fast DDS fills in the well-known ports.
  return locator;
}

bool ends_with(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

}  // namespace

std::optional<ParticipantConfig> parse_participant_profile(std::string_view text,
                                                           std::string* error) {
  ParticipantConfig config;
  if (text == "loopback") {
    config.transport = TransportProfile::kLoopback;
    return config;
  }
  if (text == "shm") {
    config.transport = TransportProfile::kShm;
    return config;
  }
  if (text == "default") {
    config.transport = TransportProfile::kDefault;
    return config;
  }
  // FILE.xml or FILE.xml:PROFILE
  std::string_view file = text;
  std::string_view profile;
  const std::size_t colon = text.rfind(':');
  if (colon != std::string_view::npos && ends_with(text.substr(0, colon), ".xml")) {
    file = text.substr(0, colon);
    profile = text.substr(colon + 1);
  }
  if (!ends_with(file, ".xml") ||
      (colon != std::string_view::npos && profile.empty() && file.size() != text.size())) {
    if (error) {
      *error = "unknown DDS profile '" + std::string(text) +
               "' (expected loopback, shm, default or FILE.xml[:PROFILE])";
    }
    return std::nullopt;
  }
  config.transport = TransportProfile::kXml;
  config.xml_file = std::string(file);
  if (!profile.empty()) config.xml_profile = std::string(profile);
  return config;
}

fdds::DomainParticipantQos participant_qos(const ParticipantConfig& config) {
  fdds::DomainParticipantQos qos = fdds::PARTICIPANT_QOS_DEFAULT;
  qos.name(config.name);
  switch (config.transport) {
    case TransportProfile::kDefault:
    case TransportProfile::kXml:
      break;
    case TransportProfile::kShm: {
      // Replaces the builtin transports (whose SHM segment is 512 KiB) by the same pair with
      // a large segment; discovery stays Fast DDS's default (multicast).
      auto& transport = qos.transport();
      transport.use_builtin_transports = false;
      auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
      udp->sendBufferSize = config.socket_buffer_bytes;
      udp->receiveBufferSize = config.socket_buffer_bytes;
      transport.user_transports.push_back(shm_transport(config.shm_segment_bytes));
      transport.user_transports.push_back(udp);
      transport.send_socket_buffer_size = config.socket_buffer_bytes;
      transport.listen_socket_buffer_size = config.socket_buffer_bytes;
      break;
    }
    case TransportProfile::kLoopback: {
      auto& transport = qos.transport();
      transport.use_builtin_transports = false;
      auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
      udp->interfaceWhiteList = {config.loopback_address};
      udp->sendBufferSize = config.socket_buffer_bytes;
      udp->receiveBufferSize = config.socket_buffer_bytes;
      udp->maxInitialPeersRange = kLoopbackPeerRange;
      transport.user_transports.push_back(shm_transport(config.shm_segment_bytes));
      transport.user_transports.push_back(udp);
      transport.send_socket_buffer_size = config.socket_buffer_bytes;
      transport.listen_socket_buffer_size = config.socket_buffer_bytes;

      auto& builtin = qos.wire_protocol().builtin;
      builtin.initialPeersList.clear();
      builtin.initialPeersList.push_back(udp_locator(config.loopback_address));
      // Explicit unicast metatraffic locators and no multicast ones: discovery is unicast only.
      builtin.metatrafficUnicastLocatorList.clear();
      builtin.metatrafficUnicastLocatorList.push_back(udp_locator(config.loopback_address));
      builtin.metatrafficMulticastLocatorList.clear();
      builtin.avoid_builtin_multicast = true;
      qos.wire_protocol().default_multicast_locator_list.clear();
      break;
    }
  }
  if (config.transport != TransportProfile::kXml) add_security_properties(config.security, qos);
  if (!config.user_data.empty())
    qos.user_data().data_vec(std::vector<eprosima::fastrtps::rtps::octet>(config.user_data.begin(),
                                                                          config.user_data.end()));
  return qos;
}

void ParticipantDeleter::operator()(fdds::DomainParticipant* participant) const {
  if (participant == nullptr) return;
  participant->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant);
}

ParticipantPtr create_participant(const ParticipantConfig& config, std::string* error,
                                  fdds::DomainParticipantListener* listener,
                                  const fdds::StatusMask& mask) {
  forward_fastdds_log_to_spdlog();
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  const auto fail = [&](std::string message) {
    if (error) *error = std::move(message);
    return ParticipantPtr();
  };
  if (const auto why = security_files_error(config.security, static_cast<int>(config.domain_id))) {
    return fail(*why);
  }
  std::string loss_error;
  const std::optional<std::uint8_t> loss = test_udp_loss_from_env(&loss_error);
  if (!loss && !loss_error.empty()) return fail(loss_error);
  // TEST ONLY (test_udp_loss.hpp): the participant's UDPv4 transports made lossy, SHM removed.
  const auto make_lossy = [&](fdds::DomainParticipantQos& qos) {
    if (!loss) return true;
    if (!apply_test_udp_loss(qos, *loss, &loss_error)) return false;
    turn_off_intraprocess_delivery();
    report_test_udp_loss_at_exit();
    spdlog::warn(
        "TEST ONLY: {}={}: participant '{}' drops {} % of the UDP DATA, DATA_FRAG, HEARTBEAT and "
        "ACKNACK messages it sends, shared memory and intraprocess delivery off; never set it in a "
        "deployment",
        kTestUdpLossEnv, *loss, qos.name().to_string(), *loss);
    return true;
  };
  fdds::DomainParticipant* participant = nullptr;
  if (config.transport == TransportProfile::kXml) {
    if (factory->load_XML_profiles_file(config.xml_file) != ReturnCode_t::RETCODE_OK) {
      return fail("cannot load Fast DDS XML profiles from '" + config.xml_file + "'");
    }
    fdds::DomainParticipantQos qos;
    if (factory->get_participant_qos_from_profile(config.xml_profile, qos) !=
        ReturnCode_t::RETCODE_OK) {
      return fail("no participant profile '" + config.xml_profile + "' in '" + config.xml_file +
                  "'");
    }
    if (config.security.enabled || !config.user_data.empty() || loss) {
      if (!make_lossy(qos)) return fail(loss_error);
      if (config.security.enabled) add_security_properties(config.security, qos);
      if (!config.user_data.empty())
        qos.user_data().data_vec(std::vector<eprosima::fastrtps::rtps::octet>(
            config.user_data.begin(), config.user_data.end()));
      participant = factory->create_participant(static_cast<fdds::DomainId_t>(config.domain_id),
                                                qos, listener, mask);
    } else {
      participant = factory->create_participant_with_profile(
          static_cast<fdds::DomainId_t>(config.domain_id), config.xml_profile, listener, mask);
    }
  } else {
    fdds::DomainParticipantQos qos = participant_qos(config);
    if (!make_lossy(qos)) return fail(loss_error);
    participant = factory->create_participant(static_cast<fdds::DomainId_t>(config.domain_id), qos,
                                              listener, mask);
  }
  if (participant == nullptr) {
    return fail(std::string("Fast DDS could not create a participant (profile ") +
                to_string(config.transport) + ", domain " + std::to_string(config.domain_id) +
                "; see the log above)");
  }
  return ParticipantPtr(participant);
}

}  // namespace litamin2::dds
