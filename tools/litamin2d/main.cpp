// litamin2d: LiTAMIN2 odometry as a DDS service. Reads sensor_msgs/PointCloud2 from
// rt/<stream>/points, runs one tracker per stream on a shared TBB arena, and publishes
// nav_msgs/Odometry on rt/<stream>/odom, map patches and a status (DiagnosticArray).
// Runs under systemd as Type=notify (READY, WATCHDOG, STOPPING, STATUS).

#include "common/cli.hpp"
#include "litamin2/config/config_reload.hpp"
#include "litamin2/config/daemon_config_yaml.hpp"
#include "litamin2/core/config_error.hpp"
#include "litamin2/daemon/dds/daemon_node.hpp"
#include "litamin2/dds/security_files.hpp"
#include "litamin2/metrics/metrics_endpoint.hpp"
#include "litamin2/service/heap_tuning.hpp"
#include "litamin2/service/logging.hpp"
#include "litamin2/service/service_loop.hpp"
#include "litamin2/version.hpp"

#include <spdlog/fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>

using namespace litamin2;
using namespace litamin2::daemon;
using service::ServiceLoop;

namespace {

/// How often the main loop turns (discovery, status, watchdog), at most.
constexpr std::chrono::milliseconds kLoopPeriod(50);

std::string describe(const DaemonConfig& c) {
  std::string streams;
  for (const StreamConfig& s : c.streams) streams += (streams.empty() ? "" : ", ") + s.id;
  std::string scheduling;
  if (c.scheduling.policy != WorkerPolicy::kOther)
    scheduling = fmt::format(", {} {} priority {}", scheduling_scope_name(c.scheduling.scope),
                             worker_policy_name(c.scheduling.policy), c.scheduling.priority);
  if (!c.scheduling.cpus.empty())
    scheduling += fmt::format(", {} on CPUs [{}]", scheduling_scope_name(c.scheduling.scope),
                              fmt::join(c.scheduling.cpus, ", "));
  return fmt::format(
      "domain {}, profile {}, streams [{}], discovery {}, threads {}, queue depth {}, heap "
      "prefault {} MiB{}{}",
      c.dds.domain, service::to_string(c.dds.profile), streams,
      c.discovery.enabled ? c.discovery.pattern : std::string("off"),
      c.threads == 0 ? std::string("auto") : std::to_string(c.threads), c.queue_depth,
      prefault_bytes(c) >> 20, c.memory.prefault_mb ? "" : " (auto)", scheduling);
}

}  // namespace

int main(int argc, char** argv) {
  // Before any thread exists, so that every thread inherits the blocked SIGTERM/SIGINT/SIGHUP.
  service::ServiceSignals signals;
  // Scan-sized buffers stay in the heap for the next scan (service/heap_tuning.hpp).
  const std::string heap_policy = service::keep_large_buffers_in_heap();

  CLI::App app{"litamin2d: LiTAMIN2 LiDAR odometry for many sensor streams over DDS"};
  tools::init_cli(app, "litamin2d");
  std::string config_file = "/etc/litamin2/litamin2d.yaml";
  bool check_config = false;
  app.add_option("-c,--config", config_file, "daemon configuration (YAML)");
  app.add_flag("--check-config", check_config, "validate the configuration and exit");
  if (const auto status = tools::parse_cli(app, argc, argv)) return *status;

  DaemonConfig config;
  try {
    config = load_daemon_config(config_file);
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
  spdlog::info("litamin2d {} starting: {}", litamin2::version(), describe(config));
  if (!heap_policy.empty()) spdlog::info("heap policy left as it is: {}", heap_policy);
  // Before any other thread allocates: they all take their memory from the touched heap.
  if (const std::size_t bytes = prefault_bytes(config); bytes > 0 && heap_policy.empty()) {
    const service::HeapPrefault prefault = service::prefault_heap(bytes);
    if (!prefault.refused.empty())
      spdlog::warn("heap not touched at start ({} of {} MiB): {}", prefault.touched_bytes >> 20,
                   bytes >> 20, prefault.refused);
    else
      spdlog::info("heap: {} MiB touched at start in {:.2f} s (memory.prefault_mb)",
                   prefault.touched_bytes >> 20, prefault.seconds);
  }

  ServiceLoop service_loop(config.watchdog.enabled);
  // Before DDS starts: a port that cannot be bound fails the start with nothing published.
  const std::unique_ptr<metrics::MetricsEndpoint> metrics =
      metrics::start_metrics_endpoint(config.metrics);
  if (!metrics) return 1;
  int exit_code = 0;
  try {
    DaemonNode node(config);
    metrics->refresh([&] { return node.metrics_text(); });
    metrics->set_ready(true);
    service_loop.notifier().ready();
    service_loop.notifier().status(node.summary());
    if (service_loop.watchdog().enabled())
      spdlog::info(
          "systemd watchdog: pinging every {} ms while healthy",
          std::chrono::duration_cast<std::chrono::milliseconds>(service_loop.watchdog().period())
              .count());
    ServiceLoop::Hooks hooks;
    hooks.poll = [&](ServiceLoop::Clock::time_point now) {
      node.poll(now);
      metrics->turn(now, [&] { return node.metrics_text(now); });
      return true;
    };
    hooks.healthy = [&](ServiceLoop::Clock::time_point now) { return node.healthy(now); };
    hooks.summary = [&](ServiceLoop::Clock::time_point now) { return node.summary(now); };
    config::ConfigReload reload(config_file, config.log_level, [](const std::string& path) {
      return load_daemon_config(path).log_level;
    });
    hooks.reload = [&reload] { reload.reload(); };
    hooks.stall_message =
        fmt::format("a frame has been in processing for over {} s: withholding the watchdog",
                    config.watchdog.stall_timeout_s);
    service_loop.run(signals, hooks, kLoopPeriod);
    metrics->set_ready(false);
    service_loop.notifier().stopping();
    const DrainResult drained = node.shutdown();
    if (!drained.complete) {
      // A frame is wedged: do not hang on it, systemd would have to kill us.
      spdlog::error("{} frame(s) still in processing at the deadline; exiting without them",
                    drained.in_flight);
      litamin2::dds::stop_fastdds_log();
      std::_Exit(1);
    }
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
