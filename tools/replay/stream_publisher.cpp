#include "replay/stream_publisher.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>

#include "litamin2/dds/plain_scan_conversion.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2_zero_copy/msg/PlainScan.h"

namespace litamin2::replay {

StreamPublisher::StreamPublisher(std::string stream, const io::ScanSequence& sequence,
                                 std::size_t first, std::size_t last,
                                 eprosima::fastdds::dds::DataWriter* writer)
    : stream_(std::move(stream)),
      sequence_(sequence),
      first_(first),
      last_(last),
      writer_(writer) {}

int StreamPublisher::matched_readers() const {
  eprosima::fastdds::dds::PublicationMatchedStatus status;
  writer_->get_publication_matched_status(status);
  return status.current_count;
}

void StreamPublisher::run(Clock::time_point start, std::chrono::nanoseconds period,
                          const std::atomic<bool>& stop, bool reliable, double timeout_s) {
  for (std::size_t i = first_; i < last_ && !stop.load(); ++i) {
    sensor_msgs::msg::PointCloud2 msg;
    dds::SerializedPointCloud2 scan;
    const bool preloaded = !preloaded_.empty();
    if (plain_) {
      // write_plain takes the stored cloud.
    } else if (preloaded) {
      scan = std::move(preloaded_[i - first_]);
    } else if (!convert(i, msg)) {
      break;
    }
    void* sample = preloaded ? static_cast<void*>(&scan) : static_cast<void*>(&msg);
    const auto slot = start + period * static_cast<std::int64_t>(i - first_);
    // Sleep in short steps so that an interrupt is seen quickly.
    while (!stop.load()) {
      const auto now = Clock::now();
      if (now >= slot) break;
      std::this_thread::sleep_for(
          std::min<Clock::duration>(slot - now, std::chrono::milliseconds(50)));
    }
    if (stop.load()) break;
    const auto before = Clock::now();
    const auto late_ns = static_cast<std::uint64_t>(std::max<std::int64_t>(
        0, std::chrono::duration_cast<std::chrono::nanoseconds>(before - slot).count()));
    if (late_ns > counters_.max_late_ns) counters_.max_late_ns = late_ns;
    if (late_ns > 5'000'000) counters_.late_over_5ms++;
    bool ok = false;
    if (plain_) {
      ok = write_plain(i, reliable, timeout_s, stop);
    } else {
      ok = writer_->write(sample);
      if (!ok && reliable && !stop.load()) {
        counters_.retried++;
        wait_for_acknowledgments(timeout_s);
        ok = writer_->write(sample);
      }
    }
    const auto after = Clock::now();
    counters_.write_ns += static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(after - before).count());
    if (ok) {
      counters_.published++;
      if (plain_) {
        counters_.points += plain_points_;
        counters_.bytes += plain_points_ * sizeof(litamin2_zero_copy::msg::PlainPoint);
      } else {
        counters_.points += preloaded ? scan.points : std::uint64_t{msg.width()} * msg.height();
        counters_.bytes += preloaded ? scan.data_bytes : msg.data().size();
      }
    } else {
      counters_.failed++;
      spdlog::warn(
          "{}: write of frame {} failed (reliable history full: readers too slow, or "
          "the writer was deleted)",
          stream_, i);
    }
    elapsed_s_ = std::chrono::duration<double>(after - start).count();
  }
}

bool StreamPublisher::convert(std::size_t i, sensor_msgs::msg::PointCloud2& msg) {
  try {
    msg = dds::to_pointcloud2(sequence_.load(i), Stamp::from_seconds(sequence_.timestamp(i)),
                              stream_);
    return true;
  } catch (const std::exception& e) {
    error_ = "scan " + std::to_string(i) + " (" + sequence_.path(i) + "): " + e.what();
    spdlog::error("{}: {}", stream_, error_);
    return false;
  }
}

bool StreamPublisher::preload() {
  preloaded_.clear();
  preloaded_.reserve(last_ - first_);
  for (std::size_t i = first_; i < last_; ++i) {
    sensor_msgs::msg::PointCloud2 msg;
    if (!convert(i, msg)) {
      preloaded_.clear();
      return false;
    }
    try {
      preloaded_.push_back(dds::serialize_pointcloud2(msg));
    } catch (const std::exception& e) {
      error_ = "scan " + std::to_string(i) + ": " + e.what();
      preloaded_.clear();
      return false;
    }
  }
  return true;
}

bool StreamPublisher::preload_plain() {
  plain_clouds_.clear();
  plain_stamps_.clear();
  plain_clouds_.reserve(last_ - first_);
  if (stream_.size() >= sizeof(litamin2_zero_copy::msg::PlainScan().frame_id())) {
    error_ = "stream id '" + stream_ + "' is too long for a PlainScan's frame_id";
    return false;
  }
  for (std::size_t i = first_; i < last_; ++i) {
    try {
      PointCloud cloud = sequence_.load(i);
      if (cloud.size() > dds::kPlainScanCapacity)
        throw std::invalid_argument(std::to_string(cloud.size()) + " points > PlainScan's " +
                                    std::to_string(dds::kPlainScanCapacity));
      if (const auto why = point_times_error(cloud)) throw std::invalid_argument(*why);
      plain_clouds_.push_back(std::move(cloud));
      plain_stamps_.push_back(Stamp::from_seconds(sequence_.timestamp(i)));
    } catch (const std::exception& e) {
      error_ = "scan " + std::to_string(i) + " (" + sequence_.path(i) + "): " + e.what();
      plain_clouds_.clear();
      plain_stamps_.clear();
      return false;
    }
  }
  plain_ = true;
  return true;
}

bool StreamPublisher::write_plain(std::size_t i, bool reliable, double timeout_s,
                                  const std::atomic<bool>& stop) {
  PointCloud cloud = std::move(plain_clouds_[i - first_]);
  plain_points_ = cloud.size();
  void* loaned = nullptr;
  ReturnCode_t rc = writer_->loan_sample(loaned);
  if (rc != ReturnCode_t::RETCODE_OK && reliable && !stop.load()) {
    // The pool is full of samples not yet acknowledged.
    counters_.retried++;
    wait_for_acknowledgments(timeout_s);
    rc = writer_->loan_sample(loaned);
  }
  if (rc != ReturnCode_t::RETCODE_OK) {
    spdlog::warn("{}: loan_sample failed (code {})", stream_, rc());
    return false;
  }
  auto* scan = static_cast<litamin2_zero_copy::msg::PlainScan*>(loaned);
  // Checked in preload_plain: the cloud fits and its times are valid.
  dds::to_plain_scan(cloud, plain_stamps_[i - first_], stream_, *scan);
  bool ok = writer_->write(loaned);
  if (!ok && reliable && !stop.load()) {
    counters_.retried++;
    wait_for_acknowledgments(timeout_s);
    ok = writer_->write(loaned);
  }
  if (!ok) writer_->discard_loan(loaned);
  return ok;
}

bool StreamPublisher::wait_for_acknowledgments(double timeout_s) {
  const double whole = std::floor(timeout_s);
  const eprosima::fastrtps::Duration_t timeout(
      static_cast<std::int32_t>(whole), static_cast<std::uint32_t>((timeout_s - whole) * 1e9));
  return writer_->wait_for_acknowledgments(timeout) == ReturnCode_t::RETCODE_OK;
}

}  // namespace litamin2::replay
