#include "litamin2/dds/participant_setup.hpp"

#include <cstdint>
#include <stdexcept>

namespace litamin2::dds {

namespace fdds = eprosima::fastdds::dds;

ParticipantConfig participant_config(const service::TransportConfig& config,
                                     const service::SecurityConfig& security,
                                     const std::string& name) {
  ParticipantConfig pc;
  pc.security = security;
  pc.domain_id = static_cast<std::uint32_t>(config.domain);
  pc.name = name;
  pc.transport = config.profile;
  if (config.profile == TransportProfile::kXml) {
    pc.xml_file = config.xml_file;
    pc.xml_profile = config.xml_profile;
  }
  return pc;
}

fdds::TypeSupport register_type(fdds::DomainParticipant* participant, fdds::TopicDataType* type) {
  fdds::TypeSupport support(type);
  if (support.register_type(participant) != ReturnCode_t::RETCODE_OK)
    throw std::runtime_error("cannot register DDS type " + support.get_type_name());
  return support;
}

}  // namespace litamin2::dds
