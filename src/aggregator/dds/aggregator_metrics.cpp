#include "litamin2/aggregator/dds/aggregator_metrics.hpp"

#include "litamin2/service/prometheus_text.hpp"
#include "litamin2/version.hpp"

#include <filesystem>
#include <system_error>

namespace litamin2::aggregator {

using service::PrometheusText;
using Type = PrometheusText::Type;

namespace {

double num(std::uint64_t v) {
  return static_cast<double>(v);
}

void scalar(PrometheusText& out, const char* name, Type type, const char* help, double value) {
  out.family(name, type, help);
  out.sample({}, value);
}

}  // namespace

std::uint64_t store_size_bytes(const std::string& path) {
  std::uint64_t bytes = 0;
  for (const std::string& file : {path, path + "-wal"}) {
    std::error_code error;
    const auto size = std::filesystem::file_size(file, error);
    if (!error) bytes += size;
  }
  return bytes;
}

std::string aggregator_metrics_text(const WorkerStatus& w, const IngestCounters& in,
                                    const std::map<std::string, OdometryStreamStatus>& odometry,
                                    std::uint64_t store_bytes) {
  PrometheusText out;
  out.family("litamin2_build_info", Type::kGauge, "litamin2's version (always 1)");
  out.sample({{"program", "litamin2-aggregator"}, {"version", litamin2::version()}}, 1);
  scalar(out, "litamin2_aggregator_keyframes_total", Type::kCounter,
         "keyframes in the mapper (recovered from the store and received)", num(w.keyframes));
  out.family("litamin2_aggregator_stream_keyframes_total", Type::kCounter,
             "keyframes in the mapper, by stream");
  for (const auto& [stream, counts] : w.streams)
    out.sample({{"stream", stream}}, num(counts.keyframes));
  scalar(out, "litamin2_aggregator_keyframes_recovered_total", Type::kCounter,
         "keyframes read from the store at start", num(w.recovered));
  scalar(out, "litamin2_aggregator_duplicates_total", Type::kCounter,
         "keyframes received again (already in the store), ignored", num(w.duplicates));
  scalar(out, "litamin2_aggregator_loops_total", Type::kCounter,
         "verified loop closures in the pose graph", num(w.loops));
  scalar(out, "litamin2_aggregator_merges_total", Type::kCounter,
         "merges of two streams' maps confirmed (groups joined)", num(w.merges));
  scalar(out, "litamin2_aggregator_optimizations_total", Type::kCounter,
         "local pose-graph optimisations", num(w.optimizations));
  out.family("litamin2_aggregator_optimization_seconds", Type::kHistogram,
             "wall time of each local pose-graph optimisation");
  out.histogram({}, w.optimize_seconds);
  scalar(out, "litamin2_aggregator_full_passes_total", Type::kCounter,
         "background full passes of the pose graph applied", num(w.full_passes));
  scalar(out, "litamin2_aggregator_batches_total", Type::kCounter, "batches of patches ingested",
         num(w.batches));
  scalar(out, "litamin2_aggregator_patches_received_total", Type::kCounter,
         "map patches received (valid or not)", num(in.received));
  out.family("litamin2_aggregator_patches_rejected_total", Type::kCounter,
             "map patches rejected by validation, by reason");
  for (const auto& [reason, count] : in.rejected_by_reason)
    out.sample({{"reason", reason}}, num(count));
  scalar(out, "litamin2_aggregator_malformed_samples_total", Type::kCounter,
         "patch and odometry samples that could not be deserialised", num(in.malformed_samples));
  scalar(out, "litamin2_aggregator_samples_lost_total", Type::kCounter,
         "patch samples DDS reported lost", num(in.samples_lost));
  scalar(out, "litamin2_aggregator_patch_writers", Type::kGauge,
         "map-patch writers (daemons) matched", static_cast<double>(in.writers));
  scalar(out, "litamin2_aggregator_queue_depth", Type::kGauge,
         "keyframes waiting for the mapping thread", static_cast<double>(in.queued));
  scalar(out, "litamin2_aggregator_queue_capacity", Type::kGauge,
         "keyframes the queue holds before the listener waits",
         static_cast<double>(in.queue_capacity));
  scalar(out, "litamin2_aggregator_map_tiles", Type::kGauge, "map tiles in the store",
         static_cast<double>(w.tiles));
  scalar(out, "litamin2_aggregator_map_tiles_published_total", Type::kCounter,
         "map tile samples written on topics.map_tiles", num(in.map_tiles_published));
  scalar(out, "litamin2_aggregator_map_tiles_deferred_total", Type::kCounter,
         "map tile changes held back by map_tiles.publish_period_s (sent later, newest only)",
         num(in.map_tiles_deferred));
  scalar(out, "litamin2_aggregator_map_pending", Type::kGauge,
         "keyframes still to be fused into the map tiles", static_cast<double>(w.map_pending));
  scalar(out, "litamin2_aggregator_store_size_bytes", Type::kGauge,
         "the SQLite store's size on disk (file and write-ahead log)", num(store_bytes));
  scalar(out, "litamin2_aggregator_store_failed", Type::kGauge,
         "1 once a store write failed (the process then exits)", w.error.empty() ? 0.0 : 1.0);
  out.family("litamin2_aggregator_odometry_received_total", Type::kCounter,
             "odometry messages received, by stream");
  for (const auto& [stream, o] : odometry) out.sample({{"stream", stream}}, num(o.received));
  out.family("litamin2_aggregator_odometry_rejected_total", Type::kCounter,
             "odometry messages with a non-finite pose, dropped, by stream");
  for (const auto& [stream, o] : odometry) out.sample({{"stream", stream}}, num(o.rejected));
  out.family("litamin2_aggregator_map_odometry_published_total", Type::kCounter,
             "map-frame poses published, by stream");
  for (const auto& [stream, o] : odometry) out.sample({{"stream", stream}}, num(o.published));
  return out.text();
}

}  // namespace litamin2::aggregator
