// cyclone_client: an independent DDS client of litamin2d (DESIGN.md section 4), written against
// the Cyclone DDS C API only, with types that Cyclone's idlc generated from the project's IDL
// files (renamed to the ROS 2 wire names by ros2_dds_idl.cmake).
//
// It publishes every scan of a KITTI-format sequence as sensor_msgs/PointCloud2 on
// rt/<stream>/points (reliable, XCDR1), waits for the daemon's nav_msgs/Odometry of that frame
// on rt/<stream>/odom (bounded wait), and writes the received poses as KITTI 3x4 rows. With
// --reference (litamin2-odometry's poses_kitti.txt of the same sequence) every received pose
// must be bit-identical to the reference pose in message form (position, normalised quaternion
// with w >= 0), as litamin2d publishes it.
//
// Cyclone is configured by CYCLONEDDS_URI, which must be set (tests use a loopback-only,
// unicast-only file): without it Cyclone would use multicast on the machine's interfaces.
//
// Exit codes: 0 all frames answered (and identical), 1 usage or I/O error, 2 the daemon's
// endpoints were not matched in time, 3 a frame got no odometry in time, 4 poses differ.

#include <dds/dds.h>

#include <CLI/CLI.hpp>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/io/trajectory.hpp"
#include "nav_msgs/msg/Odometry.h"
#include "sensor_msgs/msg/PointCloud2.h"

namespace {

constexpr std::uint8_t kFloat32 = 7;  // sensor_msgs/PointField FLOAT32

struct Stamp {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};

/// Seconds -> ROS time, the same rounding as litamin2::dds::to_time (floor, nanoseconds rounded).
Stamp to_stamp(double seconds) {
  Stamp s;
  if (!std::isfinite(seconds) || seconds < 0.0 || seconds >= 2147483647.0) return s;
  double whole = std::floor(seconds);
  auto nanos = static_cast<std::int64_t>(std::llround((seconds - whole) * 1e9));
  if (nanos >= 1'000'000'000) {
    nanos -= 1'000'000'000;
    whole += 1.0;
  }
  s.sec = static_cast<std::int32_t>(whole);
  s.nanosec = static_cast<std::uint32_t>(nanos);
  return s;
}

std::int64_t to_ns(const Stamp& s) {
  return static_cast<std::int64_t>(s.sec) * 1'000'000'000 + static_cast<std::int64_t>(s.nanosec);
}

/// A pose as geometry_msgs/Pose carries it.
struct PoseMsg {
  std::array<double, 3> position{};
  std::array<double, 4> orientation{};  // x, y, z, w
};

/// Isometry -> Pose the way litamin2d converts its poses (quaternion normalised, w >= 0).
PoseMsg to_pose_msg(const Eigen::Isometry3d& pose) {
  PoseMsg msg;
  const Eigen::Vector3d t = pose.translation();
  msg.position = {t.x(), t.y(), t.z()};
  Eigen::Quaterniond q(pose.linear());
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  msg.orientation = {q.x(), q.y(), q.z(), q.w()};
  return msg;
}

/// Pose -> isometry (quaternion normalised; identity rotation for a degenerate quaternion).
Eigen::Isometry3d from_pose_msg(const PoseMsg& msg) {
  Eigen::Quaterniond q(msg.orientation[3], msg.orientation[0], msg.orientation[1],
                       msg.orientation[2]);
  const double norm = q.norm();
  if (!(norm > 1e-12) || !std::isfinite(norm)) {
    q = Eigen::Quaterniond::Identity();
  } else {
    q.coeffs() /= norm;
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.toRotationMatrix();
  pose.translation() = Eigen::Vector3d(msg.position[0], msg.position[1], msg.position[2]);
  return pose;
}

bool bit_identical(const PoseMsg& a, const PoseMsg& b) {
  return std::memcmp(a.position.data(), b.position.data(), sizeof(a.position)) == 0 &&
         std::memcmp(a.orientation.data(), b.orientation.data(), sizeof(a.orientation)) == 0;
}

/// Owns a Cyclone entity (participant, waitset, ...): deleting it deletes its children.
class Entity {
 public:
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  ~Entity() {
    if (handle_ > 0) dds_delete(handle_);
  }
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  dds_entity_t get() const { return handle_; }

 private:
  dds_entity_t handle_;
};

/// Owns a dds_qos_t.
class Qos {
 public:
  Qos() : qos_(dds_create_qos()) {}
  ~Qos() { dds_delete_qos(qos_); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  dds_qos_t* get() const { return qos_; }

 private:
  dds_qos_t* qos_;
};

/// Reliable, volatile QoS with plain CDR (XCDR1), the representation Fast DDS 2.9 uses.
void set_common_qos(const Qos& qos, dds_duration_t max_blocking) {
  dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, max_blocking);
  dds_qset_durability(qos.get(), DDS_DURABILITY_VOLATILE);
  const dds_data_representation_id_t xcdr1[] = {DDS_DATA_REPRESENTATION_XCDR1};
  dds_qset_data_representation(qos.get(), 1, xcdr1);
}

bool check(dds_return_t rc, const char* what) {
  if (rc < 0) {
    std::fprintf(stderr, "cyclone_client: %s: %s\n", what, dds_strretcode(rc));
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Publishes a KITTI-format sequence as sensor_msgs/PointCloud2 to litamin2d and collects "
      "its nav_msgs/Odometry, using Cyclone DDS (C API) only. Needs CYCLONEDDS_URI."};
  std::string sequence_dir, stream = "cyclone", output, reference, reference_out;
  int domain = 0;
  double frame_timeout_s = 10.0, match_timeout_s = 30.0, period_s = 0.0, settle_s = 1.0;
  app.add_option("sequence", sequence_dir, "KITTI sequence folder (velodyne/*.bin)")->required();
  app.add_option("--stream", stream, "stream id: rt/<stream>/points in, rt/<stream>/odom out")
      ->capture_default_str();
  app.add_option("--domain", domain, "DDS domain id")->capture_default_str();
  app.add_option("--output", output, "KITTI poses file of the received odometry")->required();
  app.add_option("--frame-timeout", frame_timeout_s, "seconds to wait for each frame's odometry")
      ->capture_default_str();
  app.add_option("--match-timeout", match_timeout_s,
                 "seconds to wait for the daemon's reader and odometry writer")
      ->capture_default_str();
  app.add_option("--settle", settle_s,
                 "seconds to wait after both matches before the first scan, for litamin2d's "
                 "side of the discovery")
      ->capture_default_str();
  app.add_option("--period", period_s,
                 "seconds at least from one scan's publication to the next (0: as fast as "
                 "the odometry comes back)")
      ->capture_default_str();
  app.add_option("--reference", reference,
                 "KITTI poses (litamin2-odometry) every received pose must equal bit for bit");
  app.add_option("--reference-out", reference_out,
                 "write the reference poses as they read after the Pose message round trip "
                 "(so that the file is byte-identical to --output when the poses are)");
  CLI11_PARSE(app, argc, argv);

  const char* uri = std::getenv("CYCLONEDDS_URI");
  if (uri == nullptr || *uri == '\0') {
    std::fprintf(stderr,
                 "cyclone_client: CYCLONEDDS_URI is not set; refusing to run with Cyclone's "
                 "default (multicast) configuration (see tests/integration/"
                 "cyclone_loopback.xml)\n");
    return 1;
  }

  std::vector<Eigen::Isometry3d> reference_poses;
  try {
    if (!reference.empty()) reference_poses = litamin2::io::read_kitti_poses(reference);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cyclone_client: %s\n", e.what());
    return 1;
  }
  std::unique_ptr<litamin2::io::ScanSequence> sequence;
  try {
    sequence = std::make_unique<litamin2::io::ScanSequence>(sequence_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cyclone_client: %s\n", e.what());
    return 1;
  }
  const std::size_t frames = sequence->size();
  if (!reference.empty() && reference_poses.size() != frames) {
    std::fprintf(stderr, "cyclone_client: %zu reference poses for %zu scans\n",
                 reference_poses.size(), frames);
    return 1;
  }

  Entity participant(dds_create_participant(static_cast<dds_domainid_t>(domain), nullptr, nullptr));
  if (!check(participant.get(), "dds_create_participant")) return 1;
  const std::string points_name = "rt/" + stream + "/points";
  const std::string odom_name = "rt/" + stream + "/odom";
  const dds_entity_t points_topic =
      dds_create_topic(participant.get(), &sensor_msgs_msg_dds__PointCloud2__desc,
                       points_name.c_str(), nullptr, nullptr);
  const dds_entity_t odom_topic = dds_create_topic(
      participant.get(), &nav_msgs_msg_dds__Odometry__desc, odom_name.c_str(), nullptr, nullptr);
  if (!check(points_topic, "dds_create_topic (points)") ||
      !check(odom_topic, "dds_create_topic (odom)")) {
    return 1;
  }

  // Subscribe before publishing: keep every odometry sample until it is taken.
  Qos reader_qos;
  set_common_qos(reader_qos, DDS_SECS(1));
  dds_qset_history(reader_qos.get(), DDS_HISTORY_KEEP_ALL, 0);
  const dds_entity_t reader =
      dds_create_reader(participant.get(), odom_topic, reader_qos.get(), nullptr);
  Qos writer_qos;
  set_common_qos(writer_qos, DDS_SECS(10));
  dds_qset_history(writer_qos.get(), DDS_HISTORY_KEEP_ALL, 0);
  const dds_entity_t writer =
      dds_create_writer(participant.get(), points_topic, writer_qos.get(), nullptr);
  if (!check(reader, "dds_create_reader") || !check(writer, "dds_create_writer")) return 1;

  // litamin2d creates its points reader when it discovers this writer: wait for both matches.
  const auto match_deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(match_timeout_s);
  for (;;) {
    dds_publication_matched_status_t pub{};
    dds_subscription_matched_status_t sub{};
    if (!check(dds_get_publication_matched_status(writer, &pub), "publication matched") ||
        !check(dds_get_subscription_matched_status(reader, &sub), "subscription matched")) {
      return 1;
    }
    if (pub.current_count > 0 && sub.current_count > 0) break;
    if (std::chrono::steady_clock::now() > match_deadline) {
      std::fprintf(stderr,
                   "cyclone_client: no match within %.1f s (%s readers: %u, %s writers: %u)\n",
                   match_timeout_s, points_name.c_str(), pub.current_count, odom_name.c_str(),
                   sub.current_count);
      return 2;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::printf("matched litamin2d on domain %d: %s -> %s\n", domain, points_name.c_str(),
              odom_name.c_str());
  std::fflush(stdout);
  // Discovery is not symmetric: this reader can match litamin2d's odometry writer before that
  // writer has matched this reader. Its odometry is volatile, so an answer published in between
  // never comes (a CI run lost frame 0 so). Give the other side time to match.
  if (settle_s > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(settle_s));

  Entity waitset(dds_create_waitset(participant.get()));
  const dds_entity_t readcond = dds_create_readcondition(reader, DDS_ANY_STATE);
  if (!check(waitset.get(), "dds_create_waitset") || !check(readcond, "dds_create_readcondition") ||
      !check(dds_waitset_attach(waitset.get(), readcond, reader), "dds_waitset_attach")) {
    return 1;
  }

  char frame_id[] = "velodyne";
  std::array<std::string, 4> field_names = {"x", "y", "z", "intensity"};
  std::array<sensor_msgs_msg_dds__PointField_, 4> fields{};
  for (std::size_t k = 0; k < fields.size(); ++k) {
    fields[k].name = field_names[k].data();
    fields[k].offset = static_cast<std::uint32_t>(4 * k);
    fields[k].datatype = kFloat32;
    fields[k].count = 1;
  }

  std::vector<PoseMsg> received;
  std::vector<std::uint8_t> data;
  std::size_t mismatches = 0;
  double max_dt = 0.0;
  const auto start = std::chrono::steady_clock::now();
  auto next_send = start;
  for (std::size_t i = 0; i < frames; ++i) {
    litamin2::PointCloud cloud;
    try {
      cloud = sequence->load(i);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "cyclone_client: %s\n", e.what());
      return 1;
    }
    const std::size_t n = cloud.size();
    data.resize(16 * n);
    for (std::size_t p = 0; p < n; ++p) {
      const std::array<float, 4> record = {cloud.points[p].x(), cloud.points[p].y(),
                                           cloud.points[p].z(),
                                           cloud.has_intensities() ? cloud.intensities[p] : 0.0f};
      std::memcpy(data.data() + 16 * p, record.data(), 16);
    }
    const Stamp stamp = to_stamp(sequence->timestamp(i));

    sensor_msgs_msg_dds__PointCloud2_ msg{};
    msg.header.stamp.sec = stamp.sec;
    msg.header.stamp.nanosec = stamp.nanosec;
    msg.header.frame_id = frame_id;
    msg.height = 1;
    msg.width = static_cast<std::uint32_t>(n);
    msg.fields._length = msg.fields._maximum = static_cast<std::uint32_t>(fields.size());
    msg.fields._buffer = fields.data();
    msg.fields._release = false;
    msg.is_bigendian = false;  // this client runs on little-endian hosts (x86-64, aarch64)
    msg.point_step = 16;
    msg.row_step = static_cast<std::uint32_t>(16 * n);
    msg.data._length = msg.data._maximum = static_cast<std::uint32_t>(data.size());
    msg.data._buffer = data.data();
    msg.data._release = false;
    msg.is_dense = true;
    if (period_s > 0.0 && i > 0) std::this_thread::sleep_until(next_send);
    next_send =
        std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                               std::chrono::duration<double>(period_s));
    if (!check(dds_write(writer, &msg), "dds_write")) return 1;

    // Wait for this frame's odometry (matched by stamp).
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(frame_timeout_s);
    bool got = false;
    while (!got) {
      const auto left = deadline - std::chrono::steady_clock::now();
      if (left <= std::chrono::steady_clock::duration::zero()) break;
      const dds_return_t woke =
          dds_waitset_wait(waitset.get(), nullptr, 0,
                           std::chrono::duration_cast<std::chrono::nanoseconds>(left).count());
      if (!check(woke, "dds_waitset_wait")) return 1;
      void* samples[8] = {};
      dds_sample_info_t infos[8];
      const dds_return_t taken = dds_take(reader, samples, infos, 8, 8);
      if (!check(taken, "dds_take")) return 1;
      for (dds_return_t k = 0; k < taken; ++k) {
        if (!infos[k].valid_data) continue;
        const auto* odom = static_cast<const nav_msgs_msg_dds__Odometry_*>(samples[k]);
        const Stamp got_stamp{odom->header.stamp.sec, odom->header.stamp.nanosec};
        // The daemon's stamp went through seconds and back: allow one nanosecond of rounding.
        if (std::llabs(to_ns(got_stamp) - to_ns(stamp)) > 1 || got) {
          std::fprintf(stderr,
                       "cyclone_client: frame %zu: unexpected odometry stamp %d.%09u (sent "
                       "%d.%09u)\n",
                       i, got_stamp.sec, got_stamp.nanosec, stamp.sec, stamp.nanosec);
          dds_return_loan(reader, samples, taken);
          return 3;
        }
        const auto& p = odom->pose.pose;
        PoseMsg pose;
        pose.position = {p.position.x, p.position.y, p.position.z};
        pose.orientation = {p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w};
        received.push_back(pose);
        got = true;
      }
      if (taken > 0) dds_return_loan(reader, samples, taken);
    }
    if (!got) {
      std::fprintf(stderr, "cyclone_client: frame %zu: no odometry on %s within %.1f s\n", i,
                   odom_name.c_str(), frame_timeout_s);
      return 3;
    }
    if (!reference_poses.empty()) {
      const PoseMsg expected = to_pose_msg(reference_poses[i]);
      if (!bit_identical(received.back(), expected)) ++mismatches;
      const Eigen::Vector3d dt =
          from_pose_msg(received.back()).translation() - reference_poses[i].translation();
      max_dt = std::max(max_dt, dt.norm());
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(received.size());
  for (const PoseMsg& pose : received) poses.push_back(from_pose_msg(pose));
  try {
    litamin2::io::write_kitti_poses(output, poses);
    if (!reference_out.empty()) {
      std::vector<Eigen::Isometry3d> round_trip;
      for (const Eigen::Isometry3d& pose : reference_poses)
        round_trip.push_back(from_pose_msg(to_pose_msg(pose)));
      litamin2::io::write_kitti_poses(reference_out, round_trip);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cyclone_client: %s\n", e.what());
    return 1;
  }
  std::printf("%zu of %zu frames answered in %.2f s\n", received.size(), frames, seconds);
  if (!reference_poses.empty()) {
    std::printf("%zu of %zu poses bit-identical to %s (max |dt| %.3g m)\n", frames - mismatches,
                frames, reference.c_str(), max_dt);
    if (mismatches > 0) return 4;
  }
  return 0;
}
