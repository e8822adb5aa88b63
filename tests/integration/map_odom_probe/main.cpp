// map_odom_probe: reads each --stream's map-frame odometry from litamin2-aggregator
// (rt/<stream>/map_odom, nav_msgs/Odometry) and appends every message to <prefix><stream>.txt
// as "stamp_s frame_id child_frame_id x y z qx qy qz qw", flushed at once, until SIGTERM/SIGINT
// or --timeout. Prints each stream's message count and last frame_id on exit; exit 0.

#include "litamin2/dds/qos.hpp"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
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
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace fdds = eprosima::fastdds::dds;

namespace {

std::atomic<bool> g_stop{false};

class Recorder : public fdds::DataReaderListener {
 public:
  Recorder(std::string stream, const std::string& path)
      : stream(std::move(stream)), file(std::fopen(path.c_str(), "w")) {}
  ~Recorder() override {
    if (file) std::fclose(file);
  }
  void on_data_available(fdds::DataReader* reader) override {
    nav_msgs::msg::Odometry m;
    fdds::SampleInfo info;
    while (reader->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      std::lock_guard lock(mutex);
      const auto& p = m.pose().pose();
      std::fprintf(file, "%.9f %s %s %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n",
                   m.header().stamp().sec() + 1e-9 * m.header().stamp().nanosec(),
                   m.header().frame_id().c_str(), m.child_frame_id().c_str(), p.position().x(),
                   p.position().y(), p.position().z(), p.orientation().x(), p.orientation().y(),
                   p.orientation().z(), p.orientation().w());
      std::fflush(file);
      ++count;
      last_frame = m.header().frame_id();
    }
  }
  std::string stream;
  std::FILE* file;
  std::mutex mutex;
  std::size_t count = 0;
  std::string last_frame;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Records rt/<stream>/map_odom of litamin2-aggregator"};
  std::vector<std::string> streams;
  std::string prefix = "map_odom_", topic_suffix = "/map_odom";
  litamin2::testing::ProbeParticipantOptions dds_options;
  double timeout_s = 600.0;
  app.add_option("--stream", streams, "stream id (repeatable)")->required();
  app.add_option("--out", prefix, "prefix of the output files");
  dds_options.add_to(app);
  app.add_option("--timeout", timeout_s);
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGTERM, [](int) { g_stop = true; });
  std::signal(SIGINT, [](int) { g_stop = true; });

  auto participant = litamin2::testing::probe_participant(dds_options, "map_odom_probe");
  if (!participant) return 1;
  fdds::TypeSupport type(new nav_msgs::msg::OdometryPubSubType());
  type.register_type(participant.get());
  fdds::Subscriber* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  std::vector<std::unique_ptr<Recorder>> recorders;
  std::vector<fdds::DataReader*> readers;
  for (const std::string& s : streams) {
    recorders.push_back(std::make_unique<Recorder>(s, prefix + s + ".txt"));
    fdds::Topic* topic = participant->create_topic("rt/" + s + topic_suffix, type.get_type_name(),
                                                   fdds::TOPIC_QOS_DEFAULT);
    readers.push_back(subscriber->create_datareader(topic, litamin2::dds::odom_reader_qos(),
                                                    recorders.back().get()));
    if (!recorders.back()->file || !readers.back()) {
      std::fprintf(stderr, "probe: cannot record %s\n", s.c_str());
      return 1;
    }
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!g_stop && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  for (fdds::DataReader* r : readers) {
    r->set_listener(nullptr);
    subscriber->delete_datareader(r);
  }
  for (const auto& r : recorders)
    std::printf("map_odom %s: %zu message(s), last frame %s\n", r->stream.c_str(), r->count,
                r->last_frame.empty() ? "-" : r->last_frame.c_str());
  return 0;
}
