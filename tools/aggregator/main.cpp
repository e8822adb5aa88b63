// litamin2-aggregator: the central mapping process. Reads the daemons' map patches
// (rt/litamin2/map_patches), keeps every keyframe in a durable SQLite store, finds loops within
// and between streams, optimises the pose graph and publishes corrected keyframe poses, a map
// summary and a status. Runs under systemd as Type=notify (READY, WATCHDOG, STOPPING, STATUS).
// `litamin2-aggregator export` writes a store's map (PLY or PCD) and trajectories (KITTI, TUM).

#include "common/cli.hpp"
#include "litamin2/aggregator/dds/aggregator_node.hpp"
#include "litamin2/aggregator/map_export.hpp"
#include "litamin2/config/aggregator_config_yaml.hpp"
#include "litamin2/config/config_reload.hpp"
#include "litamin2/core/config_error.hpp"
#include "litamin2/dds/security_files.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/metrics/metrics_endpoint.hpp"
#include "litamin2/service/logging.hpp"
#include "litamin2/service/service_loop.hpp"
#include "litamin2/store/store_error.hpp"
#include "litamin2/version.hpp"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>
#include <optional>

using namespace litamin2;
using namespace litamin2::aggregator;

namespace {

constexpr std::chrono::milliseconds kLoopPeriod(50);
constexpr const char* kProg = "litamin2-aggregator";

std::string describe(const AggregatorConfig& c) {
  return fmt::format("domain {}, profile {}, store {}, patches from {}", c.dds.domain,
                     service::to_string(c.dds.profile), c.store.path, c.topics.map_patches);
}

/// Progress of a long rebuild on stderr, about every 10 %.
AggregatorCore::Progress progress_printer(const char* what) {
  return [what, next = std::size_t{0}](std::size_t done, std::size_t total) mutable {
    if (total < 1000 || (done < next && done != total)) return;
    next = done + total / 10;
    std::fprintf(stderr, "%s: %zu / %zu keyframes\n", what, done, total);
  };
}

/// "min_x,min_y,max_x,max_y" (metres) as a box; nullopt if it is not four numbers.
std::optional<ExportOptions::Box> parse_box(const std::string& text) {
  ExportOptions::Box b;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &b.min_x, &b.min_y, &b.max_x, &b.max_y,
                  &tail) != 4 ||
      !(b.min_x <= b.max_x) || !(b.min_y <= b.max_y))
    return std::nullopt;
  return b;
}

int run_export(ExportOptions options, const std::string& config_file) {
  const std::string store_path = options.store;
  options.progress = progress_printer("rebuilding the map");
  try {
    if (!config_file.empty()) {
      const AggregatorConfig config = load_aggregator_config(config_file);
      options.mapper = config.mapper;
      options.tiles = config.map_tiles.tiles;
    }
  } catch (const ConfigError& e) {
    return tools::usage_error(kProg, std::string("invalid configuration: ") + e.what());
  }
  try {
    const ExportResult r = export_store(options);
    std::fprintf(stderr,
                 "%s: %zu keyframe(s) of %zu stream(s), %zu loop(s), %zu voxel(s) from %zu "
                 "tile(s)\n",
                 store_path.c_str(), r.keyframes, r.streams, r.loops, r.voxels, r.tiles);
    for (const std::string& f : r.files) std::fprintf(stderr, "wrote %s\n", f.c_str());
  } catch (const store::StoreError& e) {
    return tools::runtime_error(kProg, std::string("cannot read the store: ") + e.what());
  } catch (const std::exception& e) {
    return tools::runtime_error(kProg, e.what());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Before any thread exists, so that every thread inherits the blocked SIGTERM/SIGINT/SIGHUP.
  service::ServiceSignals signals;

  CLI::App app{"litamin2-aggregator: keyframe store, loop closure and global map of every stream"};
  tools::init_cli(app, kProg);
  std::string config_file = "/etc/litamin2/litamin2-aggregator.yaml";
  bool check_config = false;
  app.add_option("-c,--config", config_file, "aggregator configuration (YAML)");
  app.add_flag("--check-config", check_config, "validate the configuration and exit");

  CLI::App* exporter = app.add_subcommand(
      "export", "write the map (PLY or PCD) and trajectories (KITTI, TUM) of a store, read-only");
  std::string store_path, map_file, trajectories, export_config, box;
  bool replay = false;
  exporter->add_option("--store", store_path, "the aggregator's store (SQLite)")->required();
  exporter->add_option("--map", map_file,
                       "global map of distributions: FILE.ply (binary PLY) or FILE.pcd (binary "
                       "PCD)");
  exporter->add_option("--trajectories", trajectories,
                       "folder for <stream>_kitti.txt and <stream>_tum.txt");
  exporter->add_flag("--replay", replay,
                     "rebuild the graph from every keyframe in canonical order (O(N) "
                     "registrations) instead of reading the stored graph");
  exporter->add_option("--mapper-config", export_config,
                       "aggregator configuration whose mapper and map_tiles sections to use "
                       "(default: built-in)");
  exporter->add_option("--box", box,
                       "only the map in MIN_X,MIN_Y,MAX_X,MAX_Y (map frame, metres): only the "
                       "tiles that meet it are read");
  if (const auto status = tools::parse_cli(app, argc, argv)) return *status;
  if (exporter->parsed()) {
    if (map_file.empty() && trajectories.empty()) {
      return tools::usage_error(app.get_name(), "export: give --map and/or --trajectories");
    }
    ExportOptions options;
    options.store = store_path;
    if (!map_file.empty() && !map_format(map_file))
      return tools::usage_error(app.get_name(), "export: --map " + map_file +
                                                    ": unsupported map format (use a .ply or "
                                                    ".pcd file name)");
    options.map_file = map_file;
    options.trajectories_dir = trajectories;
    options.replay = replay;
    if (!box.empty()) {
      options.box = parse_box(box);
      if (!options.box) {
        return tools::usage_error(app.get_name(),
                                  "export: --box wants MIN_X,MIN_Y,MAX_X,MAX_Y, got '" + box + "'");
      }
    }
    return run_export(std::move(options), export_config);
  }

  AggregatorConfig config;
  try {
    config = load_aggregator_config(config_file);
  } catch (const ConfigError& e) {
    return tools::usage_error(app.get_name(), std::string("invalid configuration: ") + e.what());
  }
  // The security files' contents (certificates, signatures, expiry, grants), here too so that
  // --check-config reports them.
  if (const auto why = litamin2::dds::security_files_error(config.security, config.dds.domain))
    return tools::usage_error(app.get_name(),
                              "invalid configuration: " + config_file + ": " + *why);
  service::setup_logging(config.log_level);
  if (check_config) {
    std::cout << config_file << ": ok (" << describe(config) << ")\n";
    return 0;
  }
  spdlog::info("litamin2-aggregator {} starting: {}", litamin2::version(), describe(config));

  service::ServiceLoop service_loop(config.watchdog.enabled);
  // Before the store and DDS: a port that cannot be bound fails the start; during the
  // store's recovery /readyz answers 503.
  const std::unique_ptr<metrics::MetricsEndpoint> metrics =
      metrics::start_metrics_endpoint(config.metrics);
  if (!metrics) return 1;
  int exit_code = 0;
  try {
    service_loop.notifier().status("recovering the store");
    AggregatorNode node(config, progress_printer("recovering"));
    metrics->refresh([&] { return node.metrics_text(); });
    metrics->set_ready(true);
    service_loop.notifier().ready();
    service_loop.notifier().status(node.summary());
    service::ServiceLoop::Hooks hooks;
    hooks.poll = [&](service::ServiceLoop::Clock::time_point now) {
      node.poll(now);
      metrics->turn(now, [&] { return node.metrics_text(); });
      if (!node.failed()) return true;
      spdlog::error("the store failed: exiting so that the service restarts");
      exit_code = 1;
      return false;
    };
    hooks.healthy = [&](service::ServiceLoop::Clock::time_point now) { return node.healthy(now); };
    hooks.summary = [&](service::ServiceLoop::Clock::time_point) { return node.summary(); };
    config::ConfigReload reload(config_file, config.log_level, [](const std::string& path) {
      return load_aggregator_config(path).log_level;
    });
    hooks.reload = [&reload] { reload.reload(); };
    hooks.stall_message =
        fmt::format("a batch has been in processing for over {} s: withholding the watchdog",
                    config.watchdog.stall_timeout_s);
    service_loop.run(signals, hooks, kLoopPeriod);
    metrics->set_ready(false);
    service_loop.notifier().stopping();
    node.shutdown();
  } catch (const store::StoreError& e) {
    spdlog::error("cannot use the store: {}", e.what());
    exit_code = 1;
  } catch (const ConfigError& e) {
    spdlog::error("invalid configuration: {}", e.what());
    exit_code = 2;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    exit_code = 1;
  }
  // Fast DDS's log thread must not deliver to spdlog once static destruction begins.
  litamin2::dds::stop_fastdds_log();
  spdlog::default_logger()->flush();
  return exit_code;
}
