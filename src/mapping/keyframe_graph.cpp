#include "litamin2/mapping/keyframe_graph.hpp"

#include "litamin2/core/so3.hpp"

#include <algorithm>
#include <iterator>

namespace litamin2::mapping {

KeyframeGraph::KeyframeGraph(int rings, double cell_size) : ring_keys_(rings), grid_(cell_size) {}

std::uint32_t KeyframeGraph::add(KeyframeNode node) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  node.stream = groups_.add(node.key, node.stamp, index);
  by_key_.emplace(node.key, index);
  ring_keys_.add(node.descriptor.ring_key);
  grid_.add(index, node.pose.translation());
  const std::uint32_t stream = node.stream;
  const std::uint64_t id = node.key.id;
  nodes_.push_back(std::move(node));
  changed_.push_back(true);
  changed_list_.push_back(index);
  update_path_lengths(stream, id);
  return index;
}

void KeyframeGraph::reserve(std::size_t nodes) {
  nodes_.reserve(nodes);
  changed_.reserve(nodes);
  changed_list_.reserve(nodes);
}

void KeyframeGraph::update_path_lengths(std::uint32_t stream, std::uint64_t from_id) {
  // From the keyframe before the new one to the end: the new keyframe's own length, and the
  // lengths after it when it arrived late (one step at the end in the usual case).
  const auto& chain = groups_.at(stream).nodes;
  auto it = chain.find(from_id);
  double length = 0.0;
  const KeyframeNode* previous = nullptr;
  if (it != chain.begin()) {
    previous = &nodes_[std::prev(it)->second];
    length = previous->path_length;
  }
  for (; it != chain.end(); ++it) {
    KeyframeNode& n = nodes_[it->second];
    if (previous) length += (n.odom_pose.translation() - previous->odom_pose.translation()).norm();
    n.path_length = length;
    previous = &n;
  }
}

void KeyframeGraph::set_pose(std::uint32_t node, const Eigen::Isometry3d& pose) {
  nodes_[node].pose = orthonormalized(pose);
  grid_.move(node, pose.translation());
  if (!changed_[node]) {
    changed_[node] = true;
    changed_list_.push_back(node);
  }
}

std::int64_t KeyframeGraph::find(const KeyframeKey& key) const {
  const auto it = by_key_.find(key);
  return it == by_key_.end() ? -1 : static_cast<std::int64_t>(it->second);
}

std::vector<std::uint32_t> KeyframeGraph::take_changed() {
  std::vector<std::uint32_t> out;
  out.swap(changed_list_);
  for (std::uint32_t n : out) changed_[n] = false;
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace litamin2::mapping
