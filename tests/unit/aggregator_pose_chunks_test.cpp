// publish.poses_chunk_keyframes: the mapping thread publishes a stream's corrected poses in
// chunks of consecutive keyframe ids and sends again only the chunks holding a keyframe that
// was added or moved. A client that keeps the latest of every chunk (as a transient-local reader
// of KeyframePoses, keyed by stream and chunk, does) ends with every keyframe's final pose, as
// with whole streams, for fewer pose entries sent.

#include "litamin2/aggregator/mapping_worker.hpp"
#include "support/process_temp_dir.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <utility>
#include <vector>

using namespace litamin2;
using namespace litamin2::aggregator;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;

namespace {

std::string fresh_store(const std::string& name) {
  return litamin2::testing::fresh_store_path("litamin2_pose_chunks_test_", name);
}

/// A client of KeyframePoses: the latest sample per (stream, chunk), and what was sent.
class ChunkClient : public AggregatorSink {
 public:
  void publish_poses(const StreamPoses& poses) override {
    latest[{poses.stream, poses.chunk}] = poses;
    entries_sent += poses.keyframes.size();
    ++samples;
  }
  void publish_summary(const MapSummary& /*summary*/) override {}

  /// Every keyframe's pose by (stream, id), from the latest sample of each chunk.
  std::map<std::pair<std::string, std::uint64_t>, Eigen::Isometry3d> poses() const {
    std::map<std::pair<std::string, std::uint64_t>, Eigen::Isometry3d> out;
    for (const auto& [key, sample] : latest)
      for (const StreamPoses::Entry& e : sample.keyframes) out[{key.first, e.id}] = e.pose;
    return out;
  }

  std::map<std::pair<std::string, std::uint64_t>, StreamPoses> latest;
  std::size_t entries_sent = 0;
  std::size_t samples = 0;
};

struct PublishedRun {
  ChunkClient client;
  std::map<std::pair<std::string, std::uint64_t>, Eigen::Isometry3d> truth;
  std::size_t loops = 0;
};

/// The out-and-back drive (loops on the way back) through a MappingWorker whose every turn's
/// poses are due; `truth` is the mapper's final poses of every keyframe.
void run(int chunk_keyframes, const std::string& store, PublishedRun& out) {
  AggregatorConfig config;
  config.mapper.place.min_travel_gap = 20.0;
  config.ingest.max_batch = 5;
  config.publish.poses_period_s = 0.0;
  config.publish.poses_chunk_keyframes = chunk_keyframes;
  config.full_pass.max_duty = 0.0;
  config.full_pass.on_stop = false;
  CoreOptions options;
  options.tiles = config.map_tiles.tiles;
  AggregatorCore core(fresh_store(store), store::OpenMode::kCreateIfMissing, config.mapper, {}, {},
                      options);
  const std::vector<Keyframe> keyframes = drive("a", out_and_back(), 0.05, 1);
  PatchQueue queue(keyframes.size());
  for (const Keyframe& kf : keyframes) ASSERT_TRUE(queue.push(kf));
  queue.close();
  MappingWorker worker(core, queue, out.client, config);
  worker.start();
  worker.stop();
  for (const StreamPoses& s : all_stream_poses(core.mapper()))
    for (const StreamPoses::Entry& e : s.keyframes) out.truth[{s.stream, e.id}] = e.pose;
  out.loops = core.mapper().loops().size();
}

}  // namespace

TEST(AggregatorPoseChunks, ChunksEndWithEveryFinalPoseAndResendOnlyWhatMoved) {
  constexpr int kChunk = 8;
  PublishedRun whole, chunked;
  run(0, "whole.db", whole);
  run(kChunk, "chunked.db", chunked);
  ASSERT_GT(chunked.loops, 2u) << "the drive closed too few loops to test anything";
  ASSERT_EQ(whole.loops, chunked.loops);

  // Each sample holds only its chunk's ids; whole streams are chunk 0 of chunk size 0.
  for (const auto& [key, sample] : chunked.client.latest) {
    EXPECT_EQ(sample.chunk_keyframes, static_cast<std::uint64_t>(kChunk));
    ASSERT_FALSE(sample.keyframes.empty());
    for (const StreamPoses::Entry& e : sample.keyframes) EXPECT_EQ(e.id / kChunk, key.second);
  }
  for (const auto& [key, sample] : whole.client.latest) EXPECT_EQ(key.second, 0u);

  // Both clients end with every keyframe at its final pose (the same computation: exact).
  for (const PublishedRun* r : {&whole, &chunked}) {
    const auto seen = r->client.poses();
    ASSERT_EQ(seen.size(), r->truth.size());
    for (const auto& [key, pose] : r->truth) {
      const auto it = seen.find(key);
      ASSERT_NE(it, seen.end()) << key.first << " keyframe " << key.second;
      EXPECT_TRUE(it->second.isApprox(pose, 0.0)) << key.first << " keyframe " << key.second;
    }
  }
  EXPECT_GT(chunked.client.latest.size(), 2u);
  // Chunks resend only what changed: fewer entries for the same end state.
  EXPECT_LT(chunked.client.entries_sent, whole.client.entries_sent)
      << "chunked " << chunked.client.entries_sent << ", whole " << whole.client.entries_sent;
}
