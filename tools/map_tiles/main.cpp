// litamin2-map-tiles: subscribes to the aggregator's map tiles (rt/litamin2/map_tiles) through a
// content filter on a box of tile keys (dds/tile_box_filter.hpp: DDS delivers only the box's
// tiles; the aggregator's writer filters them), transient-local so that the tiles published
// before it started arrive too, until --count tiles arrived or --timeout passed. Each sample is
// validated (litamin2::dds::from_map_tile; invalid ones rejected and counted, never repaired) and
// each tile's newest revision kept. Writes the means of every distribution as a PLY (--ply) and/or
// a JSON summary on stdout (--json). Exit 0 when --count tiles arrived (or, with --count 0, at the
// timeout), 1 when fewer did or the DDS setup failed, 2 on a usage error.

#include "common/cli.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/tile_box_filter.hpp"
#include "litamin2/io/ply.hpp"
#include "litamin2/msg/MapTilePubSubTypes.h"
#include "litamin2/service/security_config.hpp"
#include "map_tiles/tile_collector.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <limits>

namespace fdds = eprosima::fastdds::dds;
using namespace litamin2;

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) {
  g_stop = true;
}

nlohmann::ordered_json summary_json(
    const std::map<map_tiles::TileCollector::Key, litamin2::dds::MapTileData>& tiles,
    const map_tiles::CollectorCounts& counts, const litamin2::dds::TileBox& box) {
  nlohmann::ordered_json j;
  j["box"] = {{"ix_min", box.ix_min},
              {"ix_max", box.ix_max},
              {"iy_min", box.iy_min},
              {"iy_max", box.iy_max}};
  j["received"] = counts.received;
  j["accepted"] = counts.accepted;
  j["stale"] = counts.stale;
  j["take_failures"] = counts.take_failures;
  // Samples this client's filter evaluated: 0 when the writer filtered for it.
  j["filter_evaluations_here"] = litamin2::dds::tile_box_evaluations();
  j["rejected"] = nlohmann::ordered_json::object();
  for (const litamin2::dds::TileError e : litamin2::dds::all_tile_errors()) {
    const auto it = counts.rejected.find(litamin2::dds::to_string(e));
    j["rejected"][litamin2::dds::to_string(e)] = it == counts.rejected.end() ? 0 : it->second;
  }
  std::size_t distributions = 0;
  auto& list = j["tiles"] = nlohmann::ordered_json::array();
  for (const auto& [key, t] : tiles) {
    distributions += t.distributions.size();
    list.push_back({{"ix", t.ix},
                    {"iy", t.iy},
                    {"revision", t.revision},
                    {"tile_size", t.tile_size},
                    {"voxel_size", t.voxel_size},
                    {"frame_id", t.frame_id},
                    {"anchor_stream", t.anchor_stream},
                    {"keyframes", t.keyframes},
                    {"distributions", t.distributions.size()}});
  }
  j["distributions"] = distributions;
  return j;
}

void write_means_ply(
    const std::string& path,
    const std::map<map_tiles::TileCollector::Key, litamin2::dds::MapTileData>& tiles) {
  std::vector<float> values;
  for (const auto& [key, t] : tiles) {
    for (const Distribution& d : t.distributions) {
      values.insert(values.end(), {static_cast<float>(d.mean.x()), static_cast<float>(d.mean.y()),
                                   static_cast<float>(d.mean.z()), static_cast<float>(d.count),
                                   static_cast<float>(t.ix), static_cast<float>(t.iy)});
    }
  }
  io::write_ply_vertices(path, {"x", "y", "z", "count", "tile_ix", "tile_iy"}, values);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "litamin2-map-tiles: the aggregator's map tiles of an area, over DDS\n"
      "Fetches the aggregator's map tiles of a box of tile keys (rt/litamin2/map_tiles, "
      "content-filtered, transient-local: tiles published earlier arrive too) and writes their "
      "distributions' means as a PLY (--ply) and/or a JSON summary (--json). A tile (ix, iy) is "
      "the square [ix t, (ix + 1) t) x [iy t, (iy + 1) t) of the map frame, t its tile size. "
      "Invalid samples are rejected and counted, never repaired. Exit 0 when --count tiles "
      "arrived (with --count 0: at --timeout), 1 when fewer did or DDS failed."};
  const std::int32_t lo = std::numeric_limits<std::int32_t>::min();
  const std::int32_t hi = std::numeric_limits<std::int32_t>::max();
  litamin2::dds::TileBox box{lo, hi, lo, hi};
  std::string topic = "rt/litamin2/map_tiles", ply, profile = "loopback", pki, identity;
  int domain = 0;
  double timeout_s = 10.0;
  std::size_t count = 0, max_distributions = 1'000'000;
  bool json = false, verbose = false;
  app.add_option("--ix-min", box.ix_min, "Smallest tile ix (default: any)");
  app.add_option("--ix-max", box.ix_max, "Largest tile ix (default: any)");
  app.add_option("--iy-min", box.iy_min, "Smallest tile iy (default: any)");
  app.add_option("--iy-max", box.iy_max, "Largest tile iy (default: any)");
  app.add_option("--count", count,
                 "Exit once this many distinct tiles arrived (default 0: wait for --timeout)");
  app.add_option("--timeout", timeout_s, "Seconds to wait at most (default 10)")
      ->check(CLI::PositiveNumber);
  app.add_option("--ply", ply,
                 "Write every distribution's mean as a PLY (x, y, z, count, tile_ix, tile_iy)");
  app.add_flag("--json", json, "Print a JSON summary (counts, each tile's key and revision)");
  app.add_option("--max-distributions", max_distributions,
                 "Reject a tile with more distributions (default 1000000)")
      ->check(CLI::PositiveNumber);
  app.add_option("--topic", topic, "Topic (default rt/litamin2/map_tiles)");
  app.add_option("--domain", domain, "DDS domain id (default 0)")->check(CLI::Range(0, 232));
  app.add_option("--profile", profile,
                 "Transport: loopback (default: 127.0.0.1 and shared memory only), shm, default, "
                 "or FILE.xml[:PROFILE] (Fast DDS XML, participant profile name default "
                 "'litamin2')");
  app.add_option("--pki", pki,
                 "DDS-Security: a folder made by scripts/litamin2-pki (with --identity, e.g. an "
                 "operator's)");
  app.add_option("--identity", identity, "DDS-Security: the identity in --pki to read as");
  app.add_flag("--verbose,-v", verbose, "Log each tile received");
  bool exclusive = false;
  app.add_flag("--exclusive", exclusive,
               "Read with EXCLUSIVE ownership: the tiles of the strongest live aggregator when "
               "two run as hot standby (standby.strength > 0 on both; a SHARED reader gets "
               "none of theirs)");
  tools::init_cli(app, "litamin2-map-tiles");
  if (const auto status = tools::parse_cli(app, argc, argv)) return *status;
  const std::string prog = app.get_name();
  if (box.ix_min > box.ix_max || box.iy_min > box.iy_max)
    return tools::usage_error(prog, "--ix-min/--iy-min must not exceed --ix-max/--iy-max");
  if (pki.empty() != identity.empty())
    return tools::usage_error(prog, "--pki and --identity go together");
  std::string error;
  auto config = litamin2::dds::parse_participant_profile(profile, &error);
  if (!config) return tools::usage_error(prog, "--profile: " + error);
  config->domain_id = static_cast<std::uint32_t>(domain);
  config->name = "litamin2-map-tiles";
  if (!pki.empty()) config->security = service::pki_identity(pki, identity);

  // Logs on stderr: stdout is the JSON's.
  spdlog::set_default_logger(spdlog::stderr_color_mt("litamin2-map-tiles"));
  spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::info);

  litamin2::dds::ParticipantPtr participant = litamin2::dds::create_participant(*config, &error);
  if (!participant)
    return tools::runtime_error(prog, "cannot create the DDS participant: " + error);
  if (!litamin2::dds::register_tile_box_filter(participant.get()))
    return tools::runtime_error(prog, "cannot register the tile box content filter");
  fdds::TypeSupport type(new litamin2::msg::MapTilePubSubType());
  if (type.register_type(participant.get()) != ReturnCode_t::RETCODE_OK)
    return tools::runtime_error(prog, "cannot register the MapTile type");
  fdds::Topic* t = participant->create_topic(topic, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (!t) return tools::runtime_error(prog, "cannot create topic " + topic);
  fdds::ContentFilteredTopic* filtered = participant->create_contentfilteredtopic(
      topic + "_box", t, litamin2::dds::kTileBoxExpression, litamin2::dds::tile_box_parameters(box),
      litamin2::dds::kTileBoxFilterClass);
  if (!filtered) return tools::runtime_error(prog, "cannot create the content-filtered topic");
  fdds::Subscriber* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (!subscriber) return tools::runtime_error(prog, "cannot create the subscriber");
  litamin2::dds::TileConversionOptions options;
  options.max_distributions = max_distributions;
  map_tiles::TileCollector collector(options);
  fdds::DataReader* reader = subscriber->create_datareader(
      filtered,
      exclusive ? litamin2::dds::exclusive_ownership(litamin2::dds::map_tiles_reader_qos())
                : litamin2::dds::map_tiles_reader_qos(),
      &collector, fdds::StatusMask::data_available());
  if (!reader) return tools::runtime_error(prog, "cannot create the reader of " + topic);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(timeout_s));
  bool complete = false;
  while (!g_stop && Clock::now() < deadline) {
    if (collector.wait(count, std::min(deadline, Clock::now() + std::chrono::milliseconds(100)))) {
      complete = true;
      break;
    }
  }
  reader->set_listener(nullptr);
  const auto tiles = collector.tiles();
  const auto counts = collector.counts();
  participant.reset();

  if (!ply.empty()) {
    try {
      write_means_ply(ply, tiles);
    } catch (const std::exception& e) {
      return tools::runtime_error(prog, std::string("--ply: ") + e.what());
    }
  }
  if (json) std::cout << summary_json(tiles, counts, box).dump(2) << "\n";
  spdlog::info("{} tile(s), {} sample(s) received, {} accepted, {} rejected", tiles.size(),
               counts.received, counts.accepted, counts.received - counts.accepted);
  if (count == 0) return 0;
  if (!complete)
    return tools::runtime_error(prog, std::to_string(tiles.size()) + " of " +
                                          std::to_string(count) + " tile(s) before the timeout");
  return 0;
}
