#include "litamin2/dds/test_udp_loss.hpp"

#include <cstdlib>
#include <memory>
#include <vector>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastdds/rtps/transport/test_UDPv4TransportDescriptor.h>
#include <fastrtps/attributes/LibrarySettingsAttributes.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>

namespace litamin2::dds {

namespace frtps = eprosima::fastdds::rtps;

namespace {

std::shared_ptr<frtps::test_UDPv4TransportDescriptor> lossy_copy(
    const frtps::UDPv4TransportDescriptor& udp, std::uint8_t percent) {
  auto lossy = std::make_shared<frtps::test_UDPv4TransportDescriptor>();
  lossy->sendBufferSize = udp.sendBufferSize;
  lossy->receiveBufferSize = udp.receiveBufferSize;
  lossy->interfaceWhiteList = udp.interfaceWhiteList;
  lossy->TTL = udp.TTL;
  lossy->maxMessageSize = udp.maxMessageSize;
  lossy->maxInitialPeersRange = udp.maxInitialPeersRange;
  lossy->dropDataMessagesPercentage = percent;
  lossy->dropDataFragMessagesPercentage = percent;
  lossy->dropHeartbeatMessagesPercentage = percent;
  lossy->dropAckNackMessagesPercentage = percent;
  return lossy;
}

}  // namespace

std::optional<std::uint8_t> parse_test_udp_loss_percent(std::string_view text, std::string* error) {
  unsigned value = 0;
  bool ok = !text.empty() && text.size() <= 3;
  for (const char c : text) {
    if (c < '0' || c > '9') {
      ok = false;
      break;
    }
    value = value * 10 + static_cast<unsigned>(c - '0');
  }
  if (!ok || value > 100) {
    if (error) {
      *error = std::string(kTestUdpLossEnv) + "='" + std::string(text) +
               "': expected an integer percentage 0..100 (test only: unset it in deployments)";
    }
    return std::nullopt;
  }
  return static_cast<std::uint8_t>(value);
}

std::optional<std::uint8_t> test_udp_loss_from_env(std::string* error) {
  if (error) error->clear();
  const char* value = std::getenv(kTestUdpLossEnv);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return parse_test_udp_loss_percent(value, error);
}

bool apply_test_udp_loss(eprosima::fastdds::dds::DomainParticipantQos& qos, std::uint8_t percent,
                         std::string* error) {
  auto& transport = qos.transport();
  std::vector<std::shared_ptr<frtps::TransportDescriptorInterface>> kept;
  bool replaced = false;
  if (transport.use_builtin_transports) {
    // The builtin pair is UDPv4 + SHM: the lossy UDPv4 alone, with Fast DDS's defaults.
    transport.use_builtin_transports = false;
    kept.push_back(lossy_copy(frtps::UDPv4TransportDescriptor(), percent));
    replaced = true;
  }
  for (const auto& descriptor : transport.user_transports) {
    if (const auto udp = std::dynamic_pointer_cast<frtps::UDPv4TransportDescriptor>(descriptor)) {
      kept.push_back(lossy_copy(*udp, percent));
      replaced = true;
    } else if (std::dynamic_pointer_cast<frtps::SharedMemTransportDescriptor>(descriptor)) {
      continue;  // would bypass the loss for every peer on this host
    } else {
      kept.push_back(descriptor);
    }
  }
  if (!replaced) {
    if (error) {
      *error = std::string(kTestUdpLossEnv) +
               " is set but the participant has no UDPv4 transport to make lossy";
    }
    return false;
  }
  transport.user_transports = std::move(kept);
  return true;
}

void turn_off_intraprocess_delivery() {
  eprosima::fastrtps::LibrarySettingsAttributes settings;
  settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(settings);
}

}  // namespace litamin2::dds
