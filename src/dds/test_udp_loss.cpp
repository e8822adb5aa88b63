#include "litamin2/dds/test_udp_loss.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <random>
#include <vector>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastdds/rtps/transport/test_UDPv4TransportDescriptor.h>
#include <fastrtps/attributes/LibrarySettingsAttributes.h>
#include <fastrtps/xmlparser/XMLProfileManager.h>

namespace litamin2::dds {

namespace frtps = eprosima::fastdds::rtps;

namespace {

/// Submessages of one kind seen by the lossy transports of this process, and datagrams dropped.
struct KindCounter {
  std::atomic<std::uint64_t> seen{0};
  std::atomic<std::uint64_t> dropped{0};
};
KindCounter g_data, g_data_frag, g_heartbeat, g_acknack;

/// A filter that drops `percent` % of the messages at random (independently, as a lossy link
/// does; Fast DDS's own percentage drops every (100/N)-th message of a kind) and counts.
frtps::test_UDPv4TransportDescriptor::filter random_drop(KindCounter& counter,
                                                         std::uint8_t percent) {
  return [&counter, percent](eprosima::fastrtps::rtps::CDRMessage_t&) {
    thread_local std::mt19937 random{std::random_device{}()};
    counter.seen.fetch_add(1, std::memory_order_relaxed);
    const bool drop = std::uniform_int_distribution<int>(0, 99)(random) < percent;
    if (drop) counter.dropped.fetch_add(1, std::memory_order_relaxed);
    return drop;
  };
}

std::shared_ptr<frtps::test_UDPv4TransportDescriptor> lossy_copy(
    const frtps::UDPv4TransportDescriptor& udp, std::uint8_t percent) {
  auto lossy = std::make_shared<frtps::test_UDPv4TransportDescriptor>();
  lossy->sendBufferSize = udp.sendBufferSize;
  lossy->receiveBufferSize = udp.receiveBufferSize;
  lossy->interfaceWhiteList = udp.interfaceWhiteList;
  lossy->TTL = udp.TTL;
  lossy->maxMessageSize = udp.maxMessageSize;
  lossy->maxInitialPeersRange = udp.maxInitialPeersRange;
  // Fast DDS's percentages stay 0 (they are deterministic); the filters drop at random.
  lossy->drop_data_messages_filter_ = random_drop(g_data, percent);
  lossy->drop_data_frag_messages_filter_ = random_drop(g_data_frag, percent);
  lossy->drop_heartbeat_messages_filter_ = random_drop(g_heartbeat, percent);
  lossy->drop_ack_nack_messages_filter_ = random_drop(g_acknack, percent);
  return lossy;
}

TestUdpLossCounts::Kind read(const KindCounter& counter) {
  return {counter.seen.load(std::memory_order_relaxed),
          counter.dropped.load(std::memory_order_relaxed)};
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

TestUdpLossCounts test_udp_loss_counts() {
  return {read(g_data), read(g_data_frag), read(g_heartbeat), read(g_acknack)};
}

std::string to_string(const TestUdpLossCounts& counts) {
  const auto kind = [](const char* name, const TestUdpLossCounts::Kind& k) {
    return std::string(name) + " " + std::to_string(k.dropped) + "/" + std::to_string(k.seen);
  };
  return kind("DATA", counts.data) + ", " + kind("DATA_FRAG", counts.data_frag) + ", " +
         kind("HEARTBEAT", counts.heartbeat) + ", " + kind("ACKNACK", counts.acknack);
}

void report_test_udp_loss_at_exit() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::atexit([] {
      std::fprintf(stderr, "TEST ONLY: %s: datagrams dropped/submessages seen: %s\n",
                   kTestUdpLossEnv, to_string(test_udp_loss_counts()).c_str());
    });
  });
}

void turn_off_intraprocess_delivery() {
  eprosima::fastrtps::LibrarySettingsAttributes settings;
  settings.intraprocess_delivery = eprosima::fastrtps::INTRAPROCESS_OFF;
  eprosima::fastrtps::xmlparser::XMLProfileManager::library_settings(settings);
}

}  // namespace litamin2::dds
