// status_probe: records a DiagnosticArray status topic (rt/litamin2/status of litamin2d,
// rt/litamin2/aggregator/status of litamin2-aggregator) for the integration tests: after every
// message it rewrites --out with the latest value of every key of every status entry, one
// "<hardware_id> <key> <value>" line each, until SIGTERM or --timeout. With --pki/--identity
// it joins a secured domain (an operator may read every topic).

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "litamin2/dds/qos.hpp"
#include "support/probe_participant.hpp"

#include <CLI/CLI.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

namespace fdds = eprosima::fastdds::dds;

namespace {

std::atomic<bool> g_stop{false};

class Recorder : public fdds::DataReaderListener {
 public:
  explicit Recorder(std::string out) : out_(std::move(out)) {}
  void on_data_available(fdds::DataReader* reader) override {
    diagnostic_msgs::msg::DiagnosticArray msg;
    fdds::SampleInfo info;
    std::lock_guard lock(mutex_);
    while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      ++messages_;
      for (const auto& status : msg.status()) {
        auto& values = latest_[status.hardware_id()];
        values["level"] = std::to_string(status.level());
        values["message"] = status.message();
        for (const auto& kv : status.values()) values[kv.key()] = kv.value();
      }
    }
    const std::string tmp = out_ + ".tmp";
    {
      std::ofstream out(tmp);
      out << "status_messages - " << messages_ << "\n";
      for (const auto& [id, values] : latest_)
        for (const auto& [key, value] : values) out << id << " " << key << " " << value << "\n";
    }
    std::rename(tmp.c_str(), out_.c_str());
  }

 private:
  const std::string out_;
  std::mutex mutex_;
  std::uint64_t messages_ = 0;
  std::map<std::string, std::map<std::string, std::string>> latest_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"status_probe: records a DiagnosticArray status topic"};
  std::string topic = "rt/litamin2/status", out = "status.txt";
  litamin2::testing::ProbeParticipantOptions dds_options;
  double timeout_s = 600.0;
  app.add_option("--topic", topic);
  app.add_option("--out", out);
  dds_options.add_to(app);
  app.add_option("--timeout", timeout_s);
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGTERM, [](int) { g_stop = true; });
  std::signal(SIGINT, [](int) { g_stop = true; });

  auto participant = litamin2::testing::probe_participant(dds_options, "status_probe");
  if (!participant) return 1;
  fdds::TypeSupport type(new diagnostic_msgs::msg::DiagnosticArrayPubSubType());
  type.register_type(participant.get());
  auto* t = participant->create_topic(topic, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  Recorder recorder(out);
  fdds::DataReader* reader =
      subscriber->create_datareader(t, litamin2::dds::status_reader_qos(), &recorder);
  if (!reader) {
    std::fprintf(stderr, "status_probe: cannot read %s\n", topic.c_str());
    return 1;
  }
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  while (!g_stop && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  reader->set_listener(nullptr);
  return 0;
}
