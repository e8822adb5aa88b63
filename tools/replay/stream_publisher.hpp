#pragma once
/// Publishes one scan sequence on rt/<stream>/points, paced by a shared schedule.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <fastdds/dds/publisher/DataWriter.hpp>

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/stamp.hpp"
#include "litamin2/dds/serialized_pointcloud2.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "sensor_msgs/msg/PointCloud2.h"

namespace litamin2::replay {

using Clock = std::chrono::steady_clock;

/// Counters of one stream, readable from other threads while it runs.
struct StreamCounters {
  std::atomic<std::size_t> published{0};
  std::atomic<std::size_t> failed{0};
  /// Writes retried after waiting for acknowledgments (see run()).
  std::atomic<std::size_t> retried{0};
  std::atomic<std::uint64_t> points{0};
  std::atomic<std::uint64_t> bytes{0};
  /// Total time spent inside DataWriter::write (blocked on a full reliable history included).
  std::atomic<std::uint64_t> write_ns{0};
  /// How late the latest write started after its slot in the schedule (the publisher's own
  /// delay, e.g. its core taken by other processes), and the writes that started over 5 ms late.
  std::atomic<std::uint64_t> max_late_ns{0};
  std::atomic<std::size_t> late_over_5ms{0};
};

class StreamPublisher {
 public:
  /// Publishes frames [first, last) of `sequence` with `writer` (not owned).
  StreamPublisher(std::string stream, const io::ScanSequence& sequence, std::size_t first,
                  std::size_t last, eprosima::fastdds::dds::DataWriter* writer);

  const std::string& stream() const { return stream_; }
  std::size_t frame_count() const { return last_ - first_; }
  const StreamCounters& counters() const { return counters_; }
  /// The first error that stopped the stream (a scan that could not be read), if any.
  const std::string& error() const { return error_; }
  /// Seconds from the schedule's start to the last write's end.
  double elapsed_s() const { return elapsed_s_; }

  /// Readers currently matched with the writer.
  int matched_readers() const;

  /// Publishes every frame: frame k (counting from `first`) is written at `start + k * period`
  /// (period 0: at once); a late frame is written immediately, so the average rate is kept. A
  /// scan is read and converted before its slot, so reading overlaps the wait. Stops early
  /// when `stop` becomes true or a scan cannot be read.
  /// With `reliable`, a write that fails is retried once after waiting (at most `timeout_s`)
  /// until the readers acknowledged every sample: Fast DDS 2.9's keep-all writer sometimes
  /// fails write() on a full history at once instead of blocking for max_blocking_time
  /// ("Attempting to add Data to Full WriterCache", seen with three 2.5 MB streams at --max).
  /// A write that still fails is counted in `failed`.
  void run(Clock::time_point start, std::chrono::nanoseconds period, const std::atomic<bool>& stop,
           bool reliable, double timeout_s);

  /// Waits until every reliable reader acknowledged all samples, at most `timeout_s`.
  bool wait_for_acknowledgments(double timeout_s);
  /// Reads, converts and serialises every frame now instead of before its slot in run(); run()
  /// then writes the stored bytes, so `writer` must be of SerializedPointCloud2Type. False (with
  /// error() set) if a scan cannot be read.
  bool preload();
  /// --zero-copy: reads every frame now (as preload) and keeps the clouds; run() then writes
  /// each as a litamin2_zero_copy/PlainScan into a sample loaned from `writer`
  /// (DataWriter::loan_sample, the writer's data-sharing pool on this host), copying the stored
  /// cloud once, so `writer` must be of litamin2_zero_copy::msg::PlainScanPubSubType. False (with
  /// error() set) if a scan cannot be read or holds more points than a PlainScan.
  bool preload_plain();

 private:
  std::string stream_;
  const io::ScanSequence& sequence_;
  std::size_t first_;
  std::size_t last_;
  eprosima::fastdds::dds::DataWriter* writer_;
  StreamCounters counters_;
  std::string error_;
  /// Frames [first, last) serialised by preload(), released as they are written.
  std::vector<dds::SerializedPointCloud2> preloaded_;
  /// Frames [first, last) read by preload_plain(), with their stamps, released as written.
  std::vector<PointCloud> plain_clouds_;
  std::vector<Stamp> plain_stamps_;
  bool plain_ = false;
  std::uint64_t plain_points_ = 0;
  /// Loans a sample, writes cloud i - first_ into it and writes it (retried once as in run()).
  bool write_plain(std::size_t i, bool reliable, double timeout_s, const std::atomic<bool>& stop);
  /// Reads and converts frame i into `msg`; false (error_ set) if it cannot be read.
  bool convert(std::size_t i, sensor_msgs::msg::PointCloud2& msg);
  double elapsed_s_ = 0.0;
};

}  // namespace litamin2::replay
