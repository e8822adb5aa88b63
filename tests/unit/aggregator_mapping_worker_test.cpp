// The mapping thread publishes the poses a loop corrected before it fuses the batch's keyframes
// into the map tiles: a loop's latency (keyframe in to corrected poses out) does not include
// the tile work of its turn.

#include "litamin2/aggregator/mapping_worker.hpp"
#include "support/process_temp_dir.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

using namespace litamin2;
using namespace litamin2::aggregator;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;

namespace {

std::string fresh_store(const std::string& name) {
  return litamin2::testing::fresh_store_path("litamin2_worker_test_", name);
}

/// Records, for every pose publication, how many keyframes were still waiting for the tiles.
class PendingAtPublication : public AggregatorSink {
 public:
  explicit PendingAtPublication(const AggregatorCore& core) : core_(core) {}
  void publish_poses(const StreamPoses& /*poses*/) override {
    pending_in_turn.push_back(core_.map_pending());
  }
  void publish_summary(const MapSummary& /*summary*/) override {}

  std::vector<std::size_t> pending_in_turn;

 private:
  const AggregatorCore& core_;
};

}  // namespace

TEST(AggregatorMappingWorker, ALoopsCorrectedPosesArePublishedBeforeTheTileWork) {
  AggregatorConfig config;
  config.mapper.place.min_travel_gap = 20.0;
  config.ingest.max_batch = 5;
  config.publish.poses_period_s = 0.0;               // every turn's poses are due at once
  config.map_tiles.max_keyframes_per_turn = 100000;  // the tile work clears the queue each turn
  config.full_pass.max_duty = 0.0;
  config.full_pass.on_stop = false;  // a last pass would mark every keyframe moved again
  CoreOptions options;
  options.tiles = config.map_tiles.tiles;
  AggregatorCore core(fresh_store("worker.db"), store::OpenMode::kCreateIfMissing, config.mapper,
                      {}, {}, options);
  PendingAtPublication sink(core);
  const std::vector<Keyframe> keyframes = drive("a", out_and_back(), 0.05, 1);
  PatchQueue queue(keyframes.size());
  for (const Keyframe& kf : keyframes) ASSERT_TRUE(queue.push(kf));
  queue.close();

  struct Turn {
    std::size_t new_loops = 0;
    std::size_t latencies = 0;
    std::vector<std::size_t> pending_at_publication;
  };
  std::vector<Turn> turns;
  std::size_t seen = 0;
  MappingWorker worker(core, queue, sink, config);
  worker.observe([&](const TurnReport& report) {
    Turn turn;
    turn.new_loops = report.new_loops;
    turn.latencies = report.loop_latency_ms.size();
    turn.pending_at_publication.assign(
        sink.pending_in_turn.begin() + static_cast<std::ptrdiff_t>(seen),
        sink.pending_in_turn.end());
    seen = sink.pending_in_turn.size();
    turns.push_back(std::move(turn));
  });
  worker.start();
  worker.stop();

  std::size_t loop_turns = 0;
  for (const Turn& turn : turns) {
    if (turn.new_loops == 0) continue;
    ++loop_turns;
    // The loop's latency was measured in its own turn, at a publication made while the
    // batch's keyframes were still waiting to be fused.
    EXPECT_EQ(turn.latencies, 1u);
    ASSERT_FALSE(turn.pending_at_publication.empty());
    EXPECT_GT(turn.pending_at_publication.front(), 0u);
  }
  EXPECT_GT(loop_turns, 2u) << "the drive closed too few loops to test anything";
  EXPECT_EQ(core.map_pending(), 0u) << "the tiles were not brought up to date";
}
