// litamin2-aggregator's /metrics text from its status, and the store's size on disk.

#include "litamin2/aggregator/dds/aggregator_metrics.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace litamin2::aggregator;

namespace {

bool has_line(const std::string& text, const std::string& line) {
  return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

}  // namespace

TEST(AggregatorMetrics, StatusCountersAsSamples) {
  WorkerStatus w;
  w.keyframes = 12;
  w.recovered = 5;
  w.loops = 3;
  w.merges = 1;
  w.optimizations = 2;
  w.optimize_seconds.observe(0.004);
  w.optimize_seconds.observe(0.3);
  w.streams["car1"].keyframes = 7;
  w.streams["car2"].keyframes = 5;
  IngestCounters in;
  in.received = 14;
  in.rejected_by_reason = {{"bad_covariance", 2}};
  in.queued = 3;
  in.map_tiles_published = 9;
  in.map_tiles_deferred = 4;
  std::map<std::string, OdometryStreamStatus> odometry;
  odometry["car1"].received = 40;
  odometry["car1"].published = 38;
  const std::string text = aggregator_metrics_text(w, in, odometry, 4096);
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_keyframes_total 12")) << text;
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_stream_keyframes_total{stream=\"car1\"} 7"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_stream_keyframes_total{stream=\"car2\"} 5"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_keyframes_recovered_total 5"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_loops_total 3"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_merges_total 1"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_optimizations_total 2"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_optimization_seconds_bucket{le=\"0.005\"} 1"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_optimization_seconds_bucket{le=\"0.5\"} 2"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_optimization_seconds_count 2"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_patches_received_total 14"));
  EXPECT_TRUE(
      has_line(text, "litamin2_aggregator_patches_rejected_total{reason=\"bad_covariance\"} 2"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_queue_depth 3"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_map_tiles_published_total 9"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_map_tiles_deferred_total 4"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_store_size_bytes 4096"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_store_failed 0"));
  EXPECT_TRUE(has_line(text, "litamin2_aggregator_odometry_received_total{stream=\"car1\"} 40"));
  EXPECT_TRUE(
      has_line(text, "litamin2_aggregator_map_odometry_published_total{stream=\"car1\"} 38"));
  EXPECT_NE(text.find("litamin2_build_info{program=\"litamin2-aggregator\",version=\""),
            std::string::npos);
}

TEST(AggregatorMetrics, StoreSizeIsTheFileAndItsWal) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("metrics_store_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "a.db").string();
  EXPECT_EQ(store_size_bytes(db), 0u);  // missing: 0
  std::ofstream(db) << std::string(1000, 'x');
  EXPECT_EQ(store_size_bytes(db), 1000u);
  std::ofstream(db + "-wal") << std::string(24, 'y');
  EXPECT_EQ(store_size_bytes(db), 1024u);
  std::filesystem::remove_all(dir);
}
