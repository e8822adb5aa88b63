#include "litamin2/mapping/stream_groups.hpp"

#include <tuple>

namespace litamin2::mapping {

std::uint32_t StreamGroups::add(const KeyframeKey& key, Stamp stamp, std::uint32_t node) {
  auto [it, created] = index_.try_emplace(key.stream, static_cast<std::uint32_t>(streams_.size()));
  const std::uint32_t s = it->second;
  if (created) {
    Stream& stream = streams_.emplace_back();
    stream.name = key.stream;
    stream.parent = s;
    stream.first_stamp = stamp;
    stream.first_id = key.id;
    by_name_.emplace(key.stream, s);
  }
  Stream& stream = streams_[s];
  if (std::tie(stamp.nanoseconds, key.id) <
      std::tie(stream.first_stamp.nanoseconds, stream.first_id)) {
    stream.first_stamp = stamp;
    stream.first_id = key.id;
  }
  stream.nodes.emplace(key.id, node);
  return s;
}

bool StreamGroups::starts_before(std::uint32_t a, std::uint32_t b) const {
  const Stream& sa = streams_.at(a);
  const Stream& sb = streams_.at(b);
  return std::tie(sa.first_stamp.nanoseconds, sa.name, sa.first_id) <
         std::tie(sb.first_stamp.nanoseconds, sb.name, sb.first_id);
}

bool StreamGroups::starts_before(const std::string& a, const std::string& b) const {
  return starts_before(index(a), index(b));
}

std::string StreamGroups::first_stream() const {
  if (streams_.empty()) return {};
  std::uint32_t first = 0;
  for (std::uint32_t s = 1; s < streams_.size(); ++s)
    if (starts_before(s, first)) first = s;
  return streams_[first].name;
}

std::uint32_t StreamGroups::anchor_of(std::uint32_t stream) const {
  std::uint32_t s = stream;
  while (streams_[s].parent != s) s = streams_[s].parent;
  return s;
}

std::string StreamGroups::anchor_of(const std::string& stream) const {
  return streams_[anchor_of(index(stream))].name;
}

std::pair<std::uint32_t, std::uint32_t> StreamGroups::join(std::uint32_t a, std::uint32_t b) {
  const bool keep_a = starts_before(a, b);
  const std::uint32_t keep = keep_a ? a : b;
  const std::uint32_t moved = keep_a ? b : a;
  streams_.at(moved).parent = keep;
  return {keep, moved};
}

}  // namespace litamin2::mapping
