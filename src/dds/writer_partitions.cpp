#include "litamin2/dds/writer_partitions.hpp"

#include <fastdds/rtps/builtin/data/WriterProxyData.h>
#include <fastdds/rtps/writer/WriterDiscoveryInfo.h>

#include <algorithm>

namespace litamin2::dds {

namespace rtps = eprosima::fastrtps::rtps;

WriterPartitions::Key WriterPartitions::key(const rtps::InstanceHandle_t& handle) {
  Key k{};
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = handle.value[i];
  return k;
}

void WriterPartitions::on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                              rtps::WriterDiscoveryInfo&& info) {
  const rtps::WriterProxyData& data = info.info;
  if (topic_ != data.topicName().c_str()) return;
  const Key k = key(rtps::InstanceHandle_t(data.guid()));
  std::lock_guard lock(mutex_);
  switch (info.status) {
    case rtps::WriterDiscoveryInfo::DISCOVERED_WRITER:
    case rtps::WriterDiscoveryInfo::CHANGED_QOS_WRITER:
      writers_[k] = data.m_qos.m_partition.getNames();
      break;
    case rtps::WriterDiscoveryInfo::REMOVED_WRITER:
      writers_.erase(k);
      break;
  }
}

std::optional<std::vector<std::string>> WriterPartitions::find(
    const rtps::InstanceHandle_t& publication_handle) const {
  std::lock_guard lock(mutex_);
  const auto it = writers_.find(key(publication_handle));
  if (it == writers_.end()) return std::nullopt;
  return it->second;
}

std::size_t WriterPartitions::size() const {
  std::lock_guard lock(mutex_);
  return writers_.size();
}

}  // namespace litamin2::dds
