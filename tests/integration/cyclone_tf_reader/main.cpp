// cyclone_tf_reader: reads litamin2d's transforms as a ROS 2 node (rviz2, tf2_ros) would, with
// the Cyclone DDS C API only and types idlc generated from the project's IDL files (ROS 2 wire
// names, ros2_dds_idl.cmake).
//
// Live mode (default): subscribes to rt/tf (reliable, volatile: tf2_ros's listener QoS) and to
// rt/<stream>/odom, prints "matched" once both see the daemon's writers, and collects until
// --count transforms of the stream's odom frame arrived (or --timeout). Every transform must
// name the odometry's frames (header.frame_id -> child_frame_id) and carry its pose bit for
// bit, stamp for stamp. Transforms from --map-frame (an aggregator's map -> <stream>/odom) are
// collected apart (--map-count of them awaited): their child must be the odometry's frame and
// their stamp an odometry's. Writes "tf <stamp_ns> <parent> <child> x y z qx qy qz qw" lines.
//
// Static mode (--static): subscribes to rt/tf_static transient-local (tf2_ros's static QoS),
// after the daemon has published it, and writes the transforms of the first sample: a late
// joiner must get them.
//
// Cloud mode (--cloud TOPIC): subscribes to an aggregator's map cloud (sensor_msgs/PointCloud2,
// transient-local) and prints "cloud <frame_id> <width> <point_step> <field>:<offset>:<type>..."
// and the number of points with a finite position and a count > 0, for the first sample.
//
// CYCLONEDDS_URI must be set (tests use a loopback-only, unicast-only file).
// Exit codes: 0 done, 1 usage or DDS error, 2 no match / nothing in time, 3 a transform differs
// from its odometry or names other frames.

#include <dds/dds.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <thread>

#include "nav_msgs/msg/Odometry.h"
#include "sensor_msgs/msg/PointCloud2.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace {

struct Reading {
  std::string parent, child;
  double v[7] = {};  // x y z qx qy qz qw
};

std::int64_t to_ns(std::int32_t sec, std::uint32_t nanosec) {
  return static_cast<std::int64_t>(sec) * 1'000'000'000 + static_cast<std::int64_t>(nanosec);
}

bool check(dds_return_t rc, const char* what) {
  if (rc < 0) {
    std::fprintf(stderr, "cyclone_tf_reader: %s: %s\n", what, dds_strretcode(rc));
    return false;
  }
  return true;
}

dds_qos_t* reader_qos(bool transient_local, std::int32_t depth) {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_durability(qos,
                      transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, depth);
  const dds_data_representation_id_t xcdr1[] = {DDS_DATA_REPRESENTATION_XCDR1};
  dds_qset_data_representation(qos, 1, xcdr1);
  return qos;
}

bool matched(dds_entity_t reader) {
  dds_subscription_matched_status_t st{};
  return dds_get_subscription_matched_status(reader, &st) >= 0 && st.current_count > 0;
}

void print(std::FILE* out, std::int64_t stamp, const Reading& r) {
  std::fprintf(out, "tf %lld %s %s", static_cast<long long>(stamp), r.parent.c_str(),
               r.child.c_str());
  for (double x : r.v) std::fprintf(out, " %.17g", x);
  std::fprintf(out, "\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Reads rt/tf (checked against rt/<stream>/odom) or rt/tf_static with Cyclone DDS."};
  std::string stream, output, map_frame = "map", cloud_topic;
  int domain = 0, count = 0, map_count = 0;
  double timeout_s = 60.0;
  bool static_mode = false;
  app.add_option("--stream", stream, "stream id (rt/<stream>/odom)")->required();
  app.add_option("--domain", domain, "DDS domain id")->capture_default_str();
  app.add_option("--output", output, "file of the transforms read")->required();
  app.add_option("--count", count, "live mode: transforms of the stream to collect");
  app.add_option("--map-frame", map_frame, "parent frame of an aggregator's transforms")
      ->capture_default_str();
  app.add_option("--map-count", map_count, "live mode: map transforms of the stream to collect");
  app.add_option("--timeout", timeout_s, "seconds to wait in all")->capture_default_str();
  app.add_flag("--static", static_mode, "read rt/tf_static (transient-local) instead");
  app.add_option("--cloud", cloud_topic, "read this map cloud topic (transient-local) instead");
  CLI11_PARSE(app, argc, argv);
  const char* uri = std::getenv("CYCLONEDDS_URI");
  if (uri == nullptr || *uri == '\0') {
    std::fprintf(stderr, "cyclone_tf_reader: CYCLONEDDS_URI is not set; refusing to run\n");
    return 1;
  }
  if (!static_mode && cloud_topic.empty() && count <= 0) {
    std::fprintf(stderr, "cyclone_tf_reader: --count N (> 0) is needed in live mode\n");
    return 1;
  }
  std::FILE* out = std::fopen(output.c_str(), "w");
  if (!out) {
    std::fprintf(stderr, "cyclone_tf_reader: cannot write %s\n", output.c_str());
    return 1;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);

  const dds_entity_t participant =
      dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr);
  if (!check(participant, "dds_create_participant")) return 1;
  if (!cloud_topic.empty()) {
    const dds_entity_t topic =
        dds_create_topic(participant, &sensor_msgs_msg_dds__PointCloud2__desc, cloud_topic.c_str(),
                         nullptr, nullptr);
    if (!check(topic, "dds_create_topic (cloud)")) return 1;
    dds_qos_t* qos = reader_qos(true, 1);
    const dds_entity_t reader = dds_create_reader(participant, topic, qos, nullptr);
    dds_delete_qos(qos);
    if (!check(reader, "dds_create_reader (cloud)")) return 1;
    while (std::chrono::steady_clock::now() < deadline) {
      void* samples[1] = {};
      dds_sample_info_t infos[1];
      const dds_return_t n = dds_take(reader, samples, infos, 1, 1);
      if (!check(n, "dds_take (cloud)")) return 1;
      if (n > 0 && infos[0].valid_data) {
        const auto* c = static_cast<const sensor_msgs_msg_dds__PointCloud2_*>(samples[0]);
        std::fprintf(out, "cloud %s %u %u", c->header.frame_id, c->width, c->point_step);
        for (std::uint32_t i = 0; i < c->fields._length; ++i) {
          const auto& f = c->fields._buffer[i];
          std::fprintf(out, " %s:%u:%u", f.name, f.offset, static_cast<unsigned>(f.datatype));
        }
        // The aggregator's layout (x, y, z FLOAT32 at 0, 4, 8; count UINT32 at 12), checked
        // by the script from the line above before it trusts this count.
        std::size_t valid = 0;
        for (std::uint32_t p = 0; c->point_step == 16 && p < c->width; ++p) {
          float xyz[3];
          std::uint32_t count = 0;
          std::memcpy(xyz, c->data._buffer + 16 * p, sizeof(xyz));
          std::memcpy(&count, c->data._buffer + 16 * p + 12, sizeof(count));
          if (std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2]) && count > 0)
            ++valid;
        }
        std::fprintf(out, "\nvalid %zu\n", valid);
        dds_return_loan(reader, samples, n);
        std::fclose(out);
        dds_delete(participant);
        return 0;
      }
      if (n > 0) dds_return_loan(reader, samples, n);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::fprintf(stderr, "cyclone_tf_reader: no sample on %s in time\n", cloud_topic.c_str());
    return 2;
  }
  const dds_entity_t tf_topic =
      dds_create_topic(participant, &tf2_msgs_msg_dds__TFMessage__desc,
                       static_mode ? "rt/tf_static" : "rt/tf", nullptr, nullptr);
  if (!check(tf_topic, "dds_create_topic (tf)")) return 1;
  dds_qos_t* tf_qos = reader_qos(static_mode, static_mode ? 1 : 1000);
  const dds_entity_t tf_reader = dds_create_reader(participant, tf_topic, tf_qos, nullptr);
  dds_delete_qos(tf_qos);
  if (!check(tf_reader, "dds_create_reader (tf)")) return 1;

  dds_entity_t odom_reader = 0;
  if (!static_mode) {
    const std::string odom_name = "rt/" + stream + "/odom";
    const dds_entity_t odom_topic = dds_create_topic(participant, &nav_msgs_msg_dds__Odometry__desc,
                                                     odom_name.c_str(), nullptr, nullptr);
    if (!check(odom_topic, "dds_create_topic (odom)")) return 1;
    dds_qos_t* odom_qos = reader_qos(false, 1000);
    odom_reader = dds_create_reader(participant, odom_topic, odom_qos, nullptr);
    dds_delete_qos(odom_qos);
    if (!check(odom_reader, "dds_create_reader (odom)")) return 1;
    while (!matched(tf_reader) || !matched(odom_reader)) {
      if (std::chrono::steady_clock::now() > deadline) {
        std::fprintf(stderr, "cyclone_tf_reader: rt/tf or %s not matched in time\n",
                     odom_name.c_str());
        return 2;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::printf("matched rt/tf and %s\n", odom_name.c_str());
    std::fflush(stdout);
  }

  // Live: transforms and odometry by stamp; each transform checked once its odometry is here.
  std::map<std::int64_t, Reading> transforms, odometry, map_transforms;
  std::set<std::int64_t> map_stamps;
  int collected = 0, checked = 0, static_read = 0, map_collected = 0, map_checked = 0;
  bool done = false;
  while (!done && std::chrono::steady_clock::now() < deadline) {
    void* samples[16] = {};
    dds_sample_info_t infos[16];
    dds_return_t n = dds_take(tf_reader, samples, infos, 16, 16);
    if (!check(n, "dds_take (tf)")) return 1;
    for (dds_return_t k = 0; k < n; ++k) {
      if (!infos[k].valid_data) continue;
      const auto* msg = static_cast<const tf2_msgs_msg_dds__TFMessage_*>(samples[k]);
      for (std::uint32_t i = 0; i < msg->transforms._length; ++i) {
        const auto& t = msg->transforms._buffer[i];
        Reading r;
        r.parent = t.header.frame_id;
        r.child = t.child_frame_id;
        const auto& tr = t.transform.translation;
        const auto& q = t.transform.rotation;
        const double v[7] = {tr.x, tr.y, tr.z, q.x, q.y, q.z, q.w};
        std::memcpy(r.v, v, sizeof(v));
        const std::int64_t stamp = to_ns(t.header.stamp.sec, t.header.stamp.nanosec);
        print(out, stamp, r);
        if (static_mode) {
          ++static_read;
        } else if (r.parent == map_frame && r.child.rfind(stream + "/", 0) == 0) {
          if (!map_stamps.insert(stamp).second) {
            std::fprintf(stderr,
                         "cyclone_tf_reader: a second map transform at %lld (tf2 ignores a "
                         "repeated stamp)\n",
                         static_cast<long long>(stamp));
            return 3;
          }
          map_transforms[stamp] = r;
          ++map_collected;
        } else if (r.parent.rfind(stream + "/", 0) == 0 || r.child.rfind(stream + "/", 0) == 0) {
          transforms[stamp] = r;
          ++collected;
        }
      }
      if (static_mode) done = true;  // the first (only) sample holds every static transform
    }
    if (n > 0) dds_return_loan(tf_reader, samples, n);
    if (!static_mode) {
      n = dds_take(odom_reader, samples, infos, 16, 16);
      if (!check(n, "dds_take (odom)")) return 1;
      for (dds_return_t k = 0; k < n; ++k) {
        if (!infos[k].valid_data) continue;
        const auto* o = static_cast<const nav_msgs_msg_dds__Odometry_*>(samples[k]);
        Reading r;
        r.parent = o->header.frame_id;
        r.child = o->child_frame_id;
        const auto& p = o->pose.pose;
        const double v[7] = {p.position.x,    p.position.y,    p.position.z,   p.orientation.x,
                             p.orientation.y, p.orientation.z, p.orientation.w};
        std::memcpy(r.v, v, sizeof(v));
        odometry[to_ns(o->header.stamp.sec, o->header.stamp.nanosec)] = r;
      }
      if (n > 0) dds_return_loan(odom_reader, samples, n);
      for (auto it = transforms.begin(); it != transforms.end();) {
        const auto o = odometry.find(it->first);
        if (o == odometry.end()) {
          ++it;
          continue;
        }
        const Reading& t = it->second;
        if (t.parent != o->second.parent || t.child != o->second.child ||
            std::memcmp(t.v, o->second.v, sizeof(t.v)) != 0) {
          std::fprintf(stderr,
                       "cyclone_tf_reader: transform at %lld (%s -> %s) differs from the "
                       "odometry (%s -> %s)\n",
                       static_cast<long long>(it->first), t.parent.c_str(), t.child.c_str(),
                       o->second.parent.c_str(), o->second.child.c_str());
          return 3;
        }
        ++checked;
        it = transforms.erase(it);
      }
      for (auto it = map_transforms.begin(); it != map_transforms.end();) {
        const auto o = odometry.find(it->first);
        if (o == odometry.end()) {
          ++it;
          continue;
        }
        if (it->second.child != o->second.parent) {
          std::fprintf(stderr,
                       "cyclone_tf_reader: map transform at %lld has child %s, the odometry's "
                       "frame is %s\n",
                       static_cast<long long>(it->first), it->second.child.c_str(),
                       o->second.parent.c_str());
          return 3;
        }
        ++map_checked;
        it = map_transforms.erase(it);
      }
      if (collected >= count && transforms.empty() && map_collected >= map_count &&
          map_transforms.empty())
        done = true;
    }
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::fclose(out);
  dds_delete(participant);
  if (static_mode) {
    std::printf("%d static transform(s) read\n", static_read);
    return static_read > 0 ? 0 : 2;
  }
  std::printf("%d transform(s) of stream %s read, %d equal to their odometry bit for bit\n",
              collected, stream.c_str(), checked);
  std::printf("%d %s transform(s) of stream %s read, %d at an odometry stamp\n", map_collected,
              map_frame.c_str(), stream.c_str(), map_checked);
  return collected >= count && checked == collected && map_collected >= map_count &&
                 map_checked == map_collected
             ? 0
             : 2;
}
