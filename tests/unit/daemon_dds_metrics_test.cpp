// litamin2d's /metrics text: what the per-stream status holds, as Prometheus samples.

#include "litamin2/daemon/dds/daemon_metrics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

using namespace litamin2::daemon;
using namespace std::chrono_literals;

namespace {

/// The sample lines of `text` (no comments).
std::string samples_of(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') out += line + "\n";
  return out;
}

bool has_line(const std::string& text, const std::string& line) {
  return ("\n" + text).find("\n" + line + "\n") != std::string::npos;
}

StreamStatus stream(const std::string& id) {
  StreamStats stats;
  const auto t0 = StreamStats::Clock::now();
  for (int i = 0; i < 3; ++i) {
    stats.record_received();
    stats.record_result(t0, t0 + 3ms, i == 0, true, 100);
  }
  stats.record_bad_message("bad_row_step");
  stats.record_bad_messages("malformed_cdr", 2);
  StreamStatus s;
  s.id = id;
  s.topic = "rt/" + id + "/points";
  s.stats = stats.snapshot(t0 + 10ms);
  s.counters.dropped = 4;
  s.counters.queued = 2;
  s.reading = true;
  return s;
}

}  // namespace

TEST(DaemonMetrics, EveryStreamsCountersByLabel) {
  const std::string text = daemon_metrics_text({stream("car1"), stream("car2")});
  EXPECT_TRUE(has_line(text, "# TYPE litamin2_stream_frames_processed_total counter"));
  for (const char* id : {"car1", "car2"}) {
    const std::string l = std::string("{stream=\"") + id + "\"}";
    EXPECT_TRUE(has_line(text, "litamin2_stream_frames_received_total" + l + " 3")) << text;
    EXPECT_TRUE(has_line(text, "litamin2_stream_frames_processed_total" + l + " 3"));
    EXPECT_TRUE(has_line(text, "litamin2_stream_frames_dropped_total" + l + " 4"));
    EXPECT_TRUE(has_line(text, "litamin2_stream_keyframes_total" + l + " 1"));
    EXPECT_TRUE(has_line(text, "litamin2_stream_queue_depth" + l + " 2"));
    EXPECT_TRUE(has_line(text, "litamin2_stream_reading" + l + " 1"));
    EXPECT_TRUE(has_line(text, "litamin2_stream_map_distributions" + l + " 100"));
    EXPECT_TRUE(has_line(text, std::string("litamin2_stream_bad_messages_total{stream=\"") + id +
                                   "\",reason=\"bad_row_step\"} 1"));
    EXPECT_TRUE(has_line(text, std::string("litamin2_stream_bad_messages_total{stream=\"") + id +
                                   "\",reason=\"malformed_cdr\"} 2"));
    // Three frames of 3 ms: none at le=0.0025, all at le=0.005, and +Inf = _count.
    const std::string b = std::string("litamin2_stream_latency_seconds_bucket{stream=\"") + id;
    EXPECT_TRUE(has_line(text, b + "\",le=\"0.0025\"} 0"));
    EXPECT_TRUE(has_line(text, b + "\",le=\"0.005\"} 3"));
    EXPECT_TRUE(has_line(text, b + "\",le=\"+Inf\"} 3"));
    EXPECT_TRUE(has_line(text, "litamin2_stream_latency_seconds_count" + l + " 3"));
  }
  EXPECT_TRUE(has_line(text, "litamin2_streams 2"));
  EXPECT_NE(text.find("litamin2_build_info{program=\"litamin2d\",version=\""), std::string::npos);
}

TEST(DaemonMetrics, NoStreamsStillTypesEveryFamily) {
  const std::string text = daemon_metrics_text({});
  EXPECT_TRUE(has_line(text, "# TYPE litamin2_stream_latency_seconds histogram"));
  EXPECT_TRUE(has_line(text, "# TYPE litamin2_stream_bad_messages_total counter"));
  // Only the build info and the stream count have samples.
  const std::string s = samples_of(text);
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 2) << s;
  EXPECT_TRUE(has_line(text, "litamin2_streams 0"));
}

TEST(DaemonMetrics, MergeCountersOfAStreamOfSeveralSensors) {
  StreamStatus merged = stream("car1");
  ScanMergerCounters m;
  m.frames = 10;
  m.incomplete_frames = 3;
  m.sensors.resize(2);
  m.sensors[0] = {10, 0, 1, 0};
  m.sensors[1] = {7, 3, 0, 2};
  merged.merge = m;
  const std::string text = daemon_metrics_text({merged, stream("car2")});
  EXPECT_TRUE(
      has_line(text, "litamin2_stream_merged_frames_total{stream=\"car1\",complete=\"true\"} 7"))
      << text;
  EXPECT_TRUE(
      has_line(text, "litamin2_stream_merged_frames_total{stream=\"car1\",complete=\"false\"} 3"));
  EXPECT_TRUE(has_line(
      text,
      "litamin2_stream_sensor_scans_total{stream=\"car1\",sensor=\"0\",outcome=\"merged\"} 10"));
  EXPECT_TRUE(has_line(text,
                       "litamin2_stream_sensor_scans_total{stream=\"car1\",sensor=\"0\",outcome="
                       "\"out_of_order\"} 1"));
  EXPECT_TRUE(has_line(
      text,
      "litamin2_stream_sensor_scans_total{stream=\"car1\",sensor=\"1\",outcome=\"missing\"} 3"));
  EXPECT_TRUE(has_line(
      text, "litamin2_stream_sensor_scans_total{stream=\"car1\",sensor=\"1\",outcome=\"late\"} 2"));
  // A single-sensor stream has no merge samples.
  EXPECT_EQ(text.find("merged_frames_total{stream=\"car2\""), std::string::npos);
  EXPECT_EQ(text.find("sensor_scans_total{stream=\"car2\""), std::string::npos);
}
