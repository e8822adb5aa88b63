#include "litamin2/daemon/dds/status_message.hpp"

#include "litamin2/dds/diagnostics.hpp"
#include "litamin2/dds/time_conversion.hpp"

namespace litamin2::daemon {

using dds::fixed_number;
using dds::key_value;

diagnostic_msgs::msg::DiagnosticArray make_status_message(const std::vector<StreamStatus>& streams,
                                                          Stamp stamp) {
  diagnostic_msgs::msg::DiagnosticArray array;
  array.header().stamp(dds::to_time(stamp));
  array.header().frame_id("");
  for (const StreamStatus& s : streams) {
    diagnostic_msgs::msg::DiagnosticStatus status;
    status.level(s.level);
    status.name("litamin2d: " + s.id);
    status.message(s.message);
    status.hardware_id(s.id);
    auto& v = status.values();
    v.push_back(key_value("topic", s.topic));
    v.push_back(key_value("reader", !s.moved_to.empty() ? "moved to member " + s.moved_to
                                    : !s.reading        ? "waiting for a publisher"
                                    : s.reliable        ? "reliable"
                                                        : "best_effort"));
    v.push_back(key_value("frames_per_second", fixed_number(s.stats.frames_per_second, 2)));
    v.push_back(key_value("latency_p50_ms", fixed_number(s.stats.latency_p50_ms, 3)));
    v.push_back(key_value("latency_p99_ms", fixed_number(s.stats.latency_p99_ms, 3)));
    v.push_back(key_value("latency_max_ms", fixed_number(s.stats.latency_max_ms, 3)));
    v.push_back(key_value("frames_received", std::to_string(s.stats.frames_received)));
    v.push_back(key_value("frames_processed", std::to_string(s.stats.frames_processed)));
    v.push_back(key_value("frames_dropped", std::to_string(s.counters.dropped)));
    v.push_back(key_value("frames_failed", std::to_string(s.counters.failed)));
    v.push_back(key_value("frames_queued", std::to_string(s.counters.queued)));
    v.push_back(key_value("frames_unregistered", std::to_string(s.stats.frames_unregistered)));
    v.push_back(key_value("bad_messages", std::to_string(s.stats.bad_messages)));
    for (const auto& [reason, count] : s.stats.bad_message_reasons)
      v.push_back(key_value("bad_messages." + reason, std::to_string(count)));
    v.push_back(key_value("frames_out_of_order", std::to_string(s.stats.frames_out_of_order)));
    v.push_back(key_value("tracking_cpu_s", fixed_number(s.stats.tracking_cpu_s, 6)));
    v.push_back(key_value("points_non_finite", std::to_string(s.stats.points_non_finite)));
    v.push_back(key_value("samples_lost", std::to_string(s.samples_lost)));
    v.push_back(key_value("keyframes", std::to_string(s.stats.keyframes)));
    v.push_back(key_value("map_size", std::to_string(s.stats.map_size)));
    if (s.merge) {
      // Several sensors: merged frames, and per sensor (in the listed order of `topic`) its
      // scans merged, merged frames without it, and its scans rejected.
      const ScanMergerCounters& m = *s.merge;
      v.push_back(key_value("merged_frames", std::to_string(m.frames)));
      v.push_back(key_value("merged_frames_incomplete", std::to_string(m.incomplete_frames)));
      for (std::size_t i = 0; i < m.sensors.size(); ++i) {
        const std::string prefix = "sensor." + std::to_string(i) + ".";
        const SensorMergeCounters& c = m.sensors[i];
        v.push_back(key_value(prefix + "scans", std::to_string(c.scans)));
        v.push_back(key_value(prefix + "missing", std::to_string(c.missing)));
        v.push_back(key_value(prefix + "out_of_order", std::to_string(c.out_of_order)));
        v.push_back(key_value(prefix + "late", std::to_string(c.late)));
      }
    }
    array.status().push_back(std::move(status));
  }
  return array;
}

}  // namespace litamin2::daemon
