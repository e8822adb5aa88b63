#pragma once
/// The streams the mapper has seen: each stream's chain of keyframe ids with the odometry path
/// length along it, and the groups of streams that loops have joined (union-find). A group's
/// poses are in the frame of its anchor stream; of two groups that meet, the one whose anchor's
/// first keyframe comes first in canonical order (canonical_before: stamp, then stream, then
/// id) keeps its frame, so that groups, anchors and the map frame depend only on the set of
/// keyframes, not on the order in which they arrived.

#include "litamin2/core/keyframe.hpp"

#include <cstdint>
#include <map>
#include <string>
#include <utility>

namespace litamin2::mapping {

class StreamGroups {
 public:
  struct Stream {
    /// The stream's canonically first keyframe.
    Stamp first_stamp;
    std::uint64_t first_id = 0;
    /// Union-find parent (a stream name); the root is the group's anchor.
    std::string parent;
    /// Keyframe ids present, with the odometry path length from the stream's first keyframe
    /// (kept up to date by the mapper).
    std::map<std::uint64_t, double> path_length;
  };

  /// Records a keyframe (with path length 0 until the mapper sets it); a new stream starts a
  /// group of its own.
  Stream& add(const KeyframeKey& key, Stamp stamp);

  /// Stream a's first keyframe comes before stream b's (canonical order).
  bool starts_before(const std::string& a, const std::string& b) const;
  /// The stream whose first keyframe is the first of all (empty without keyframes).
  std::string first_stream() const;
  /// The anchor of the stream's group.
  std::string anchor_of(const std::string& stream) const;
  /// Joins the groups of anchors a and b (a != b): the one that starts first keeps its frame.
  /// Returns {kept anchor, moved anchor}.
  std::pair<std::string, std::string> join(const std::string& a, const std::string& b);

  const Stream& at(const std::string& stream) const { return streams_.at(stream); }
  Stream& at(const std::string& stream) { return streams_.at(stream); }
  /// Every stream by name.
  const std::map<std::string, Stream>& streams() const { return streams_; }

 private:
  std::map<std::string, Stream> streams_;
};

}  // namespace litamin2::mapping
