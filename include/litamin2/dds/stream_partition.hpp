#pragma once
/// Map patches travel in one DDS partition per stream: litamin2d writes a stream's patches
/// through a Publisher whose only partition is the stream id, and the aggregator reads every
/// partition ("*") and keeps a patch only if its stream id is one of the partitions of the
/// writer that sent it. With DDS-Security the permissions grant a daemon
/// rt/litamin2/map_patches only in the partitions of its own streams (scripts/litamin2-pki), so
/// a daemon's identity can neither write into another daemon's partition (Fast DDS refuses the
/// writer) nor name another stream inside its own (the aggregator refuses the patch).
/// docs/security.md "Stream binding".

#include <fastdds/dds/publisher/qos/PublisherQos.hpp>
#include <fastdds/dds/subscriber/qos/SubscriberQos.hpp>

#include <string>
#include <vector>

namespace litamin2::dds {

/// The rejection reason of a patch whose stream id is not a partition of its writer
/// (patches_rejected.stream_not_bound in the aggregator's status).
inline constexpr const char* kStreamNotBound = "stream_not_bound";

/// The Publisher of one stream's map patches: partition `stream_id` only.
eprosima::fastdds::dds::PublisherQos stream_publisher_qos(const std::string& stream_id);

/// The Subscriber of every stream's map patches: partition "*", which Fast DDS matches with
/// every named partition (not with the default, empty one).
eprosima::fastdds::dds::SubscriberQos every_stream_subscriber_qos();

/// `stream_id` is one of `writer_partitions`, compared as plain strings: a writer's partition
/// written as a pattern ("*", "car_?") binds only the stream of that literal name, and the
/// default partition (none or "") binds no stream.
bool stream_bound(const std::string& stream_id, const std::vector<std::string>& writer_partitions);

}  // namespace litamin2::dds
