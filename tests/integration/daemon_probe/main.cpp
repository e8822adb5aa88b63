// daemon_probe: the test subscriber of the litamin2d integration tests. Reads rt/<stream>/odom
// of the given streams and rt/litamin2/status, then checks that every stream received the
// expected number of odometry messages, in order, and (when a reference poses file is given)
// that each pose is the offline tool's pose exactly: the position bit for bit and the
// orientation equal to the quaternion litamin2::dds::to_pose_msg makes of the offline pose.
// Exit status 0 when every check passed, 1 otherwise; bounded by --timeout.

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/io/trajectory.hpp"
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
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

namespace fdds = eprosima::fastdds::dds;
using namespace litamin2;

namespace {

struct Received {
  geometry_msgs::msg::Pose pose;
  /// Wall-clock time of reception (seconds since the epoch), for --arrivals-out.
  double arrival = 0.0;
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  std::string frame_id, child_frame_id;
};

class OdomListener : public fdds::DataReaderListener {
 public:
  void on_data_available(fdds::DataReader* reader) override {
    nav_msgs::msg::Odometry msg;
    fdds::SampleInfo info;
    while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      std::lock_guard lock(mutex);
      const double arrival =
          std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
              .count();
      samples.push_back({msg.pose().pose(), arrival, msg.header().stamp().sec(),
                         msg.header().stamp().nanosec(), msg.header().frame_id(),
                         msg.child_frame_id()});
    }
  }
  void on_subscription_matched(fdds::DataReader*,
                               const fdds::SubscriptionMatchedStatus& status) override {
    matched = status.current_count;
  }
  std::mutex mutex;
  std::vector<Received> samples;
  std::atomic<int> matched{0};
};

class StatusListener : public fdds::DataReaderListener {
 public:
  void on_data_available(fdds::DataReader* reader) override {
    diagnostic_msgs::msg::DiagnosticArray msg;
    fdds::SampleInfo info;
    while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      std::lock_guard lock(mutex);
      ++count;
      for (const auto& status : msg.status()) {
        auto& values = latest[status.hardware_id()];
        values.clear();
        for (const auto& kv : status.values()) values[kv.key()] = kv.value();
        values["level"] = std::to_string(status.level());
      }
    }
  }
  std::mutex mutex;
  int count = 0;
  std::map<std::string, std::map<std::string, std::string>> latest;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"daemon_probe: counts and checks litamin2d's odometry"};
  std::vector<std::string> streams;
  litamin2::testing::ProbeParticipantOptions dds_options;
  std::string ready_file, poses_out, arrivals_out;
  std::size_t expect = 0;
  double timeout_s = 60.0;
  app.add_option("--stream", streams, "ID or ID=REFERENCE_POSES_KITTI (repeatable)")->required();
  app.add_option("--expect", expect, "odometry messages expected per stream")->required();
  dds_options.add_to(app);
  bool exclusive = false;
  app.add_flag("--exclusive", exclusive,
               "read the odometry with EXCLUSIVE ownership (litamin2d hot standby)");
  app.add_option("--timeout", timeout_s);
  app.add_option("--ready-file", ready_file, "created once every odom reader is matched");
  app.add_option("--poses-out", poses_out, "prefix of files with the received poses (KITTI)");
  std::string status_out;
  app.add_option("--status-out", status_out,
                 "prefix of files with each stream's last status, one 'key value' a line");
  app.add_option("--arrivals-out", arrivals_out,
                 "prefix of files with one line per message: reception time (s since the epoch), "
                 "header stamp (s), x, y, z");
  CLI11_PARSE(app, argc, argv);

  litamin2::dds::ParticipantPtr participant =
      litamin2::testing::probe_participant(dds_options, "daemon_probe");
  if (!participant) return 1;
  fdds::TypeSupport odom_type(new nav_msgs::msg::OdometryPubSubType());
  fdds::TypeSupport status_type(new diagnostic_msgs::msg::DiagnosticArrayPubSubType());
  odom_type.register_type(participant.get());
  status_type.register_type(participant.get());
  fdds::Subscriber* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);

  struct StreamProbe {
    std::string id, reference;
    std::unique_ptr<OdomListener> listener = std::make_unique<OdomListener>();
  };
  std::vector<StreamProbe> probes;
  for (const std::string& s : streams) {
    StreamProbe p;
    const auto eq = s.find('=');
    p.id = s.substr(0, eq);
    if (eq != std::string::npos) p.reference = s.substr(eq + 1);
    auto* topic = participant->create_topic("rt/" + p.id + "/odom", odom_type.get_type_name(),
                                            fdds::TOPIC_QOS_DEFAULT);
    subscriber->create_datareader(topic,
                                  exclusive ? litamin2::dds::exclusive_odom_reader_qos(1000)
                                            : litamin2::dds::odom_reader_qos(1000),
                                  p.listener.get());
    probes.push_back(std::move(p));
  }
  StatusListener status_listener;
  auto* status_topic = participant->create_topic("rt/litamin2/status", status_type.get_type_name(),
                                                 fdds::TOPIC_QOS_DEFAULT);
  subscriber->create_datareader(status_topic, litamin2::dds::status_reader_qos(), &status_listener);

  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(timeout_s));
  bool ready_written = false;
  for (;;) {
    bool all_matched = true, all_received = true;
    for (auto& p : probes) {
      all_matched = all_matched && p.listener->matched.load() > 0;
      std::lock_guard lock(p.listener->mutex);
      all_received = all_received && p.listener->samples.size() >= expect;
    }
    if (all_matched && !ready_written && !ready_file.empty()) {
      std::ofstream(ready_file) << "ready\n";
      ready_written = true;
    }
    if (all_received) break;
    if (Clock::now() > deadline) {
      std::printf("timed out after %.0f s with messages missing\n", timeout_s);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Wait for a status that reports every frame of every stream processed: a status period, or
  // longer where a lossy link lost the last status and it is resent after the next heartbeat
  // (bounded at 10 s; the check below then fails on the last status received).
  const auto status_deadline = Clock::now() + std::chrono::seconds(10);
  for (;;) {
    bool all_reported = true;
    {
      std::lock_guard lock(status_listener.mutex);
      for (auto& p : probes)
        all_reported = all_reported &&
                       status_listener.latest[p.id]["frames_processed"] == std::to_string(expect);
    }
    if (all_reported || Clock::now() > status_deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }

  bool ok = true;
  for (auto& p : probes) {
    std::vector<Received> samples;
    {
      std::lock_guard lock(p.listener->mutex);
      samples = p.listener->samples;
    }
    std::printf("stream %s: %zu odometry message(s), expected %zu\n", p.id.c_str(), samples.size(),
                expect);
    if (samples.size() != expect) ok = false;
    for (std::size_t i = 1; i < samples.size(); ++i) {
      const auto a = std::make_pair(samples[i - 1].sec, samples[i - 1].nanosec);
      const auto b = std::make_pair(samples[i].sec, samples[i].nanosec);
      if (!(a < b)) {
        std::printf("stream %s: message %zu is not after message %zu\n", p.id.c_str(), i, i - 1);
        ok = false;
        break;
      }
    }
    if (!samples.empty() && (samples[0].frame_id != p.id + "/odom" ||
                             samples[0].child_frame_id != p.id + "/base_link")) {
      std::printf("stream %s: frames %s -> %s\n", p.id.c_str(), samples[0].frame_id.c_str(),
                  samples[0].child_frame_id.c_str());
      ok = false;
    }
    if (!poses_out.empty()) {
      std::vector<Eigen::Isometry3d> poses;
      for (const Received& r : samples) poses.push_back(litamin2::dds::from_pose_msg(r.pose));
      io::write_kitti_poses(poses_out + p.id + ".txt", poses);
    }
    if (!arrivals_out.empty()) {
      std::FILE* f = std::fopen((arrivals_out + p.id + ".txt").c_str(), "w");
      for (const Received& r : samples)
        if (f)
          std::fprintf(f, "%.6f %d.%09u %.6f %.6f %.6f\n", r.arrival, r.sec, r.nanosec,
                       r.pose.position().x(), r.pose.position().y(), r.pose.position().z());
      if (f) std::fclose(f);
    }
    if (p.reference.empty()) continue;
    const std::vector<Eigen::Isometry3d> reference = io::read_kitti_poses(p.reference);
    std::size_t exact = 0;
    double max_translation = 0, max_rotation = 0;
    for (std::size_t i = 0; i < samples.size() && i < reference.size(); ++i) {
      const geometry_msgs::msg::Pose expected = litamin2::dds::to_pose_msg(reference[i]);
      const auto& got = samples[i].pose;
      const bool same = got.position().x() == expected.position().x() &&
                        got.position().y() == expected.position().y() &&
                        got.position().z() == expected.position().z() &&
                        got.orientation().x() == expected.orientation().x() &&
                        got.orientation().y() == expected.orientation().y() &&
                        got.orientation().z() == expected.orientation().z() &&
                        got.orientation().w() == expected.orientation().w();
      if (same) ++exact;
      const Eigen::Isometry3d pose = litamin2::dds::from_pose_msg(got);
      max_translation =
          std::max(max_translation, (pose.translation() - reference[i].translation()).norm());
      max_rotation =
          std::max(max_rotation, (pose.linear() - reference[i].linear()).cwiseAbs().maxCoeff());
    }
    std::printf(
        "stream %s: %zu of %zu pose(s) bit-identical to %s (max |dt| %.3g m, max |dR| "
        "%.3g)\n",
        p.id.c_str(), exact, reference.size(), p.reference.c_str(), max_translation, max_rotation);
    if (exact != reference.size() || samples.size() != reference.size()) ok = false;
  }
  {
    std::lock_guard lock(status_listener.mutex);
    std::printf("status: %d message(s)\n", status_listener.count);
    if (status_listener.count == 0) ok = false;
    for (auto& p : probes) {
      auto& v = status_listener.latest[p.id];
      std::printf(
          "status %s: processed %s, dropped %s, bad %s, p50 %s ms, p99 %s ms, map %s, tracking "
          "cpu %s s, keyframes %s\n",
          p.id.c_str(), v["frames_processed"].c_str(), v["frames_dropped"].c_str(),
          v["bad_messages"].c_str(), v["latency_p50_ms"].c_str(), v["latency_p99_ms"].c_str(),
          v["map_size"].c_str(), v["tracking_cpu_s"].c_str(), v["keyframes"].c_str());
      if (v["frames_processed"] != std::to_string(expect) || v["frames_dropped"] != "0") ok = false;
      if (!status_out.empty()) {
        std::FILE* f = std::fopen((status_out + p.id + ".txt").c_str(), "w");
        if (!f) {
          ok = false;
          continue;
        }
        for (const auto& [key, value] : v) std::fprintf(f, "%s %s\n", key.c_str(), value.c_str());
        std::fclose(f);
      }
    }
  }
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
