// cyclone_diagnostics_reader: reads rt/diagnostics as a ROS 2 tool (rqt_robot_monitor,
// diagnostic_aggregator) would, with the Cyclone DDS C API only and types idlc generated from
// the project's IDL files (ROS 2 wire names, ros2_dds_idl.cmake). Reader QoS: reliable,
// volatile, keep-last 1 (diagnostic_aggregator's subscription to /diagnostics).
//
// Collects DiagnosticArray samples until, for every --expect NAME, a status of that name with
// the key --key (default frames_processed) at a value >= --min arrived, or --timeout. Prints
// "matched" when a writer is matched, and for every expected name the last such status as
// "status <name> level <level> <key>=<value> values <number of key/values>".
//
// CYCLONEDDS_URI must be set (tests use a loopback-only, unicast-only file).
// Exit codes: 0 all expected statuses seen, 1 usage or DDS error, 2 not in time.

#include <dds/dds.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "diagnostic_msgs/msg/DiagnosticArray.h"

namespace {

bool check(dds_return_t rc, const char* what) {
  if (rc < 0) {
    std::fprintf(stderr, "cyclone_diagnostics_reader: %s: %s\n", what, dds_strretcode(rc));
    return false;
  }
  return true;
}

struct Seen {
  int level = -1;
  double value = -1.0;
  std::size_t values = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Reads rt/diagnostics (diagnostic_msgs/DiagnosticArray) with Cyclone DDS."};
  std::string topic_name = "rt/diagnostics", key = "frames_processed";
  std::vector<std::string> expected;
  int domain = 0;
  double min_value = 1.0, timeout_s = 60.0;
  app.add_option("--topic", topic_name, "topic")->capture_default_str();
  app.add_option("--domain", domain, "DDS domain id")->capture_default_str();
  app.add_option("--expect", expected, "status names to wait for")->required();
  app.add_option("--key", key, "key whose value must reach --min")->capture_default_str();
  app.add_option("--min", min_value, "smallest value of --key")->capture_default_str();
  app.add_option("--timeout", timeout_s, "seconds to wait in all")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const char* uri = std::getenv("CYCLONEDDS_URI");
  if (uri == nullptr || *uri == '\0') {
    std::fprintf(stderr, "cyclone_diagnostics_reader: CYCLONEDDS_URI is not set; refusing\n");
    return 1;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  const dds_entity_t participant =
      dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr);
  if (!check(participant, "dds_create_participant")) return 1;
  const dds_entity_t topic =
      dds_create_topic(participant, &diagnostic_msgs_msg_dds__DiagnosticArray__desc,
                       topic_name.c_str(), nullptr, nullptr);
  if (!check(topic, "dds_create_topic")) return 1;
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 1);
  const dds_data_representation_id_t xcdr1[] = {DDS_DATA_REPRESENTATION_XCDR1};
  dds_qset_data_representation(qos, 1, xcdr1);
  const dds_entity_t reader = dds_create_reader(participant, topic, qos, nullptr);
  dds_delete_qos(qos);
  if (!check(reader, "dds_create_reader")) return 1;

  bool announced = false;
  std::map<std::string, Seen> seen;
  auto done = [&] {
    for (const std::string& name : expected) {
      const auto it = seen.find(name);
      if (it == seen.end() || it->second.value < min_value) return false;
    }
    return true;
  };
  while (std::chrono::steady_clock::now() < deadline && !done()) {
    if (!announced) {
      dds_subscription_matched_status_t st{};
      if (dds_get_subscription_matched_status(reader, &st) >= 0 && st.current_count > 0) {
        std::printf("matched %s (%d writer(s))\n", topic_name.c_str(), st.current_count);
        std::fflush(stdout);
        announced = true;
      }
    }
    void* samples[8] = {};
    dds_sample_info_t infos[8];
    const dds_return_t n = dds_take(reader, samples, infos, 8, 8);
    if (!check(n, "dds_take")) return 1;
    for (dds_return_t i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const auto* a = static_cast<const diagnostic_msgs_msg_dds__DiagnosticArray_*>(samples[i]);
      for (std::uint32_t s = 0; s < a->status._length; ++s) {
        const auto& st = a->status._buffer[s];
        Seen entry;
        entry.level = static_cast<int>(static_cast<unsigned char>(st.level));
        entry.values = st.values._length;
        for (std::uint32_t v = 0; v < st.values._length; ++v)
          if (key == st.values._buffer[v].key)
            entry.value = std::strtod(st.values._buffer[v].value, nullptr);
        seen[st.name] = entry;
      }
    }
    if (n > 0) dds_return_loan(reader, samples, n);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (const std::string& name : expected) {
    const auto it = seen.find(name);
    if (it == seen.end()) {
      std::printf("missing %s\n", name.c_str());
      continue;
    }
    std::printf("status %s level %d %s=%g values %zu\n", name.c_str(), it->second.level,
                key.c_str(), it->second.value, it->second.values);
  }
  dds_delete(participant);
  return done() ? 0 : 2;
}
