#pragma once
/// The streams the mapper has seen: each stream's chain of keyframes (id -> node), and the
/// groups of streams that loops have joined (union-find). A group's poses are in the frame of
/// its anchor stream; of two groups that meet, the one whose anchor's first keyframe comes
/// first in canonical order (canonical_before: stamp, then stream, then id) keeps its frame,
/// so that groups, anchors and the map frame depend only on the set of keyframes, not on the
/// order in which they arrived. Streams are numbered in the order they are first seen, so
/// that hot loops compare integers, not names.

#include "litamin2/core/keyframe.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace litamin2::mapping {

class StreamGroups {
 public:
  struct Stream {
    std::string name;
    /// The stream's canonically first keyframe.
    Stamp first_stamp;
    std::uint64_t first_id = 0;
    /// Union-find parent (a stream index); the root is the group's anchor.
    std::uint32_t parent = 0;
    /// Keyframe ids present, with the node each is (KeyframeGraph's numbering).
    std::map<std::uint64_t, std::uint32_t> nodes;
  };

  /// Records a keyframe as node `node`; a new stream starts a group of its own. Returns the
  /// stream's index.
  std::uint32_t add(const KeyframeKey& key, Stamp stamp, std::uint32_t node);

  /// Stream a's first keyframe comes before stream b's (canonical order).
  bool starts_before(std::uint32_t a, std::uint32_t b) const;
  bool starts_before(const std::string& a, const std::string& b) const;
  /// The stream whose first keyframe is the first of all (empty without keyframes).
  std::string first_stream() const;
  /// The anchor of the stream's group.
  std::uint32_t anchor_of(std::uint32_t stream) const;
  std::string anchor_of(const std::string& stream) const;
  /// Joins the groups of anchors a and b (a != b): the one that starts first keeps its frame.
  /// Returns {kept anchor, moved anchor}.
  std::pair<std::uint32_t, std::uint32_t> join(std::uint32_t a, std::uint32_t b);

  /// The stream's index; throws std::out_of_range for an unknown name.
  std::uint32_t index(const std::string& stream) const { return index_.at(stream); }
  bool contains(const std::string& stream) const { return index_.count(stream) > 0; }
  const Stream& at(std::uint32_t stream) const { return streams_.at(stream); }
  const Stream& at(const std::string& stream) const { return streams_.at(index(stream)); }
  /// Every stream, by index.
  const std::vector<Stream>& streams() const { return streams_; }
  /// Stream indices ordered by name.
  const std::map<std::string, std::uint32_t>& by_name() const { return by_name_; }

 private:
  std::vector<Stream> streams_;
  std::unordered_map<std::string, std::uint32_t> index_;
  std::map<std::string, std::uint32_t> by_name_;
};

}  // namespace litamin2::mapping
