#include "litamin2/mapping/stream_groups.hpp"

#include <tuple>

namespace litamin2::mapping {

StreamGroups::Stream& StreamGroups::add(const KeyframeKey& key, Stamp stamp) {
  auto [it, created] = streams_.try_emplace(key.stream);
  Stream& stream = it->second;
  if (created) stream.parent = key.stream;
  if (created || std::tie(stamp.nanoseconds, key.id) <
                     std::tie(stream.first_stamp.nanoseconds, stream.first_id)) {
    stream.first_stamp = stamp;
    stream.first_id = key.id;
  }
  stream.path_length.emplace(key.id, 0.0);
  return stream;
}

bool StreamGroups::starts_before(const std::string& a, const std::string& b) const {
  const Stream& sa = streams_.at(a);
  const Stream& sb = streams_.at(b);
  return std::tie(sa.first_stamp.nanoseconds, a, sa.first_id) <
         std::tie(sb.first_stamp.nanoseconds, b, sb.first_id);
}

std::string StreamGroups::first_stream() const {
  std::string first;
  for (const auto& [name, stream] : streams_)
    if (first.empty() || starts_before(name, first)) first = name;
  return first;
}

std::string StreamGroups::anchor_of(const std::string& stream) const {
  std::string s = stream;
  while (streams_.at(s).parent != s) s = streams_.at(s).parent;
  return s;
}

std::pair<std::string, std::string> StreamGroups::join(const std::string& a, const std::string& b) {
  const bool keep_a = starts_before(a, b);
  const std::string& keep = keep_a ? a : b;
  const std::string& moved = keep_a ? b : a;
  streams_.at(moved).parent = keep;
  return {keep, moved};
}

}  // namespace litamin2::mapping
