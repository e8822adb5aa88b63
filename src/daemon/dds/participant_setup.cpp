#include "litamin2/daemon/dds/participant_setup.hpp"

#include <chrono>
#include <cstdint>
#include <stdexcept>

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

dds::ParticipantConfig participant_config(const DdsConfig& config, const std::string& name) {
  dds::ParticipantConfig pc;
  pc.domain_id = static_cast<std::uint32_t>(config.domain);
  pc.name = name;
  switch (config.profile) {
    case TransportProfile::loopback:
      pc.transport = dds::TransportProfile::kLoopback;
      break;
    case TransportProfile::shm:
      pc.transport = dds::TransportProfile::kShm;
      break;
    case TransportProfile::default_profile:
      pc.transport = dds::TransportProfile::kDefault;
      break;
    case TransportProfile::xml:
      pc.transport = dds::TransportProfile::kXml;
      pc.xml_file = config.xml_file;
      pc.xml_profile = config.xml_profile;
      break;
  }
  return pc;
}

fdds::TypeSupport register_type(fdds::DomainParticipant* participant, fdds::TopicDataType* type) {
  fdds::TypeSupport support(type);
  if (support.register_type(participant) != ReturnCode_t::RETCODE_OK)
    throw std::runtime_error("cannot register DDS type " + support.get_type_name());
  return support;
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace litamin2::daemon
