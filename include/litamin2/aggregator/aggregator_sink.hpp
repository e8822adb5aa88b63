#pragma once
/// Where the mapping thread's results go: the DDS writers in the aggregator, a recorder in
/// tests. Called from the mapping thread only.

#include "litamin2/aggregator/aggregator_outputs.hpp"

namespace litamin2::aggregator {

class AggregatorSink {
 public:
  virtual ~AggregatorSink() = default;
  virtual void publish_poses(const StreamPoses& poses) = 0;
  virtual void publish_summary(const MapSummary& summary) = 0;
  /// A map tile that changed (the DDS node publishes it on topics.map_tiles; tests and
  /// benchmarks record it; this default drops it).
  virtual void publish_tile(const TileOutput& /*tile*/) {}
};

}  // namespace litamin2::aggregator
