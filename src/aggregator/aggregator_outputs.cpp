#include "litamin2/aggregator/aggregator_outputs.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace litamin2::aggregator {

namespace {

std::vector<StreamPoses> collect(const mapping::Mapper& mapper,
                                 const std::set<std::string>* wanted) {
  const std::string anchor = mapper.map_anchor();
  std::map<std::string, StreamPoses> by_stream;
  for (const mapping::KeyframePose& p : mapper.poses()) {
    if (wanted && !wanted->count(p.key.stream)) continue;
    StreamPoses& s = by_stream[p.key.stream];
    s.stream = p.key.stream;
    s.anchor = p.frame;
    s.in_map_frame = !anchor.empty() && p.frame == anchor;
    const mapping::KeyframeNode* kf = mapper.node(p.key);
    s.keyframes.push_back({p.key.id, kf ? kf->stamp : Stamp{}, p.pose});
  }
  std::vector<StreamPoses> out;
  out.reserve(by_stream.size());
  for (auto& [stream, s] : by_stream) {
    std::sort(s.keyframes.begin(), s.keyframes.end(),
              [](const auto& a, const auto& b) { return a.id < b.id; });
    if (const auto c = mapper.correction(stream)) {
      s.correction = c->pose;
      s.anchor = c->frame;
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

std::vector<StreamPoses> all_stream_poses(const mapping::Mapper& mapper) {
  return collect(mapper, nullptr);
}

std::vector<StreamPoses> stream_poses(const mapping::Mapper& mapper,
                                      const std::vector<std::string>& streams) {
  const std::set<std::string> wanted(streams.begin(), streams.end());
  return collect(mapper, &wanted);
}

MapSummary map_summary(const mapping::Mapper& mapper, const std::vector<Distribution>& global_map,
                       std::size_t max_means) {
  MapSummary s;
  s.anchor = mapper.map_anchor();
  s.voxel_size = mapper.config().map_voxel_size;
  s.voxels = global_map.size();
  const mapping::MapperStats stats = mapper.stats();
  s.keyframes = stats.keyframes;
  s.streams = stats.streams;
  s.loops = mapper.loops().size();
  s.optimizations = stats.optimizations;
  if (!global_map.empty()) {
    s.min_bound = s.max_bound = global_map.front().mean;
    for (const Distribution& d : global_map) {
      s.min_bound = s.min_bound.cwiseMin(d.mean);
      s.max_bound = s.max_bound.cwiseMax(d.mean);
    }
  }
  if (max_means > 0 && !global_map.empty()) {
    const std::size_t n = std::min(max_means, global_map.size());
    s.means.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      s.means.push_back(global_map[i * global_map.size() / n].mean.cast<float>());
  }
  return s;
}

}  // namespace litamin2::aggregator
