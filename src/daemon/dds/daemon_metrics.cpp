#include "litamin2/daemon/dds/daemon_metrics.hpp"

#include "litamin2/service/prometheus_text.hpp"
#include "litamin2/version.hpp"

#include <cstdint>
#include <functional>

namespace litamin2::daemon {

using service::PrometheusText;
using Type = PrometheusText::Type;

namespace {

void per_stream(PrometheusText& out, const std::vector<StreamStatus>& streams, const char* name,
                Type type, const char* help, const std::function<double(const StreamStatus&)>& f) {
  out.family(name, type, help);
  for (const StreamStatus& s : streams) out.sample({{"stream", s.id}}, f(s));
}

double num(std::uint64_t v) {
  return static_cast<double>(v);
}

}  // namespace

std::string daemon_metrics_text(const std::vector<StreamStatus>& streams) {
  PrometheusText out;
  out.family("litamin2_build_info", Type::kGauge, "litamin2's version (always 1)");
  out.sample({{"program", "litamin2d"}, {"version", litamin2::version()}}, 1);
  out.family("litamin2_streams", Type::kGauge, "streams the daemon tracks");
  out.sample({}, static_cast<double>(streams.size()));
  per_stream(out, streams, "litamin2_stream_frames_received_total", Type::kCounter,
             "valid scans received (bad messages are not frames)",
             [](const StreamStatus& s) { return num(s.stats.frames_received); });
  per_stream(out, streams, "litamin2_stream_frames_processed_total", Type::kCounter,
             "scans whose odometry was published",
             [](const StreamStatus& s) { return num(s.stats.frames_processed); });
  per_stream(out, streams, "litamin2_stream_frames_dropped_total", Type::kCounter,
             "scans dropped because the stream fell behind (oldest first) or at shutdown",
             [](const StreamStatus& s) { return num(s.counters.dropped); });
  per_stream(out, streams, "litamin2_stream_frames_failed_total", Type::kCounter,
             "scans whose processing failed",
             [](const StreamStatus& s) { return num(s.counters.failed); });
  per_stream(out, streams, "litamin2_stream_frames_unregistered_total", Type::kCounter,
             "scans whose registration did not converge (pose from the motion prediction)",
             [](const StreamStatus& s) { return num(s.stats.frames_unregistered); });
  per_stream(out, streams, "litamin2_stream_frames_out_of_order_total", Type::kCounter,
             "valid scans refused because their stamp was not later than the last one's",
             [](const StreamStatus& s) { return num(s.stats.frames_out_of_order); });
  out.family("litamin2_stream_bad_messages_total", Type::kCounter,
             "messages rejected by validation, by reason");
  for (const StreamStatus& s : streams)
    for (const auto& [reason, count] : s.stats.bad_message_reasons)
      out.sample({{"stream", s.id}, {"reason", reason}}, num(count));
  per_stream(out, streams, "litamin2_stream_points_non_finite_total", Type::kCounter,
             "points with a NaN/Inf coordinate dropped from received scans",
             [](const StreamStatus& s) { return num(s.stats.points_non_finite); });
  per_stream(out, streams, "litamin2_stream_samples_lost_total", Type::kCounter,
             "samples DDS reported lost on the stream's reader",
             [](const StreamStatus& s) { return num(s.samples_lost); });
  per_stream(out, streams, "litamin2_stream_keyframes_total", Type::kCounter,
             "keyframes made (each one a map patch)",
             [](const StreamStatus& s) { return num(s.stats.keyframes); });
  per_stream(out, streams, "litamin2_stream_tracking_cpu_seconds_total", Type::kCounter,
             "CPU time the stream's tracker spent registering scans",
             [](const StreamStatus& s) { return s.stats.tracking_cpu_s; });
  out.family("litamin2_stream_latency_seconds", Type::kHistogram,
             "scan arrival to odometry published");
  for (const StreamStatus& s : streams) out.histogram({{"stream", s.id}}, s.stats.latency_seconds);
  // Streams of several sensors only.
  out.family("litamin2_stream_merged_frames_total", Type::kCounter,
             "frames merged from several sensors' scans, by completeness");
  for (const StreamStatus& s : streams)
    if (s.merge) {
      out.sample({{"stream", s.id}, {"complete", "true"}},
                 num(s.merge->frames - s.merge->incomplete_frames));
      out.sample({{"stream", s.id}, {"complete", "false"}}, num(s.merge->incomplete_frames));
    }
  out.family("litamin2_stream_sensor_scans_total", Type::kCounter,
             "scans of a stream's sensor (index in its topics), by outcome: merged, missing "
             "(a merged frame without it), out_of_order, late (rejected)");
  for (const StreamStatus& s : streams)
    if (s.merge)
      for (std::size_t i = 0; i < s.merge->sensors.size(); ++i) {
        const SensorMergeCounters& c = s.merge->sensors[i];
        const std::string sensor = std::to_string(i);
        out.sample({{"stream", s.id}, {"sensor", sensor}, {"outcome", "merged"}}, num(c.scans));
        out.sample({{"stream", s.id}, {"sensor", sensor}, {"outcome", "missing"}}, num(c.missing));
        out.sample({{"stream", s.id}, {"sensor", sensor}, {"outcome", "out_of_order"}},
                   num(c.out_of_order));
        out.sample({{"stream", s.id}, {"sensor", sensor}, {"outcome", "late"}}, num(c.late));
      }
  per_stream(out, streams, "litamin2_stream_queue_depth", Type::kGauge,
             "scans waiting to be processed",
             [](const StreamStatus& s) { return static_cast<double>(s.counters.queued); });
  per_stream(out, streams, "litamin2_stream_reading", Type::kGauge,
             "1 when a publisher was found and a reader created",
             [](const StreamStatus& s) { return s.reading ? 1.0 : 0.0; });
  per_stream(out, streams, "litamin2_stream_map_distributions", Type::kGauge,
             "distributions in the stream's local voxel map",
             [](const StreamStatus& s) { return static_cast<double>(s.stats.map_size); });
  return out.text();
}

}  // namespace litamin2::daemon
