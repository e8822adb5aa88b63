#pragma once
/// DDS setup shared by the daemon's and the aggregator's nodes: the participant of a `dds:`
/// config section, type registration and wall-clock stamps.

#include "litamin2/daemon/daemon_config.hpp"
#include "litamin2/dds/participant_factory.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <string>

namespace litamin2::daemon {

/// The participant of a `dds:` section, named `name` in discovery tools.
dds::ParticipantConfig participant_config(const DdsConfig& config, const std::string& name);

/// Registers `type` (owned by the result) with `participant`; throws std::runtime_error naming
/// the type when Fast DDS refuses it.
eprosima::fastdds::dds::TypeSupport register_type(
    eprosima::fastdds::dds::DomainParticipant* participant,
    eprosima::fastdds::dds::TopicDataType* type);

/// Wall-clock time, seconds since the Unix epoch (stamps of published messages).
double wall_seconds();

}  // namespace litamin2::daemon
