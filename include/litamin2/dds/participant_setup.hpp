#pragma once
/// DDS setup shared by the daemon's and the aggregator's nodes: the participant of the `dds:`
/// and `security:` config sections and type registration.

#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/service/transport_config.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <string>

namespace litamin2::dds {

/// The participant of a `dds:` and a `security:` section, named `name` in discovery tools.
ParticipantConfig participant_config(const service::TransportConfig& config,
                                     const service::SecurityConfig& security,
                                     const std::string& name);

/// Registers `type` (owned by the result) with `participant`; throws std::runtime_error naming
/// the type when Fast DDS refuses it.
eprosima::fastdds::dds::TypeSupport register_type(
    eprosima::fastdds::dds::DomainParticipant* participant,
    eprosima::fastdds::dds::TopicDataType* type);

}  // namespace litamin2::dds
