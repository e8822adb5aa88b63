#include "litamin2/daemon/scan_merger.hpp"

#include <cmath>
#include <stdexcept>

namespace litamin2::daemon {

std::optional<std::string> scan_merger_config_error(const ScanMergerConfig& config) {
  if (!(config.window_s > 0.0 && config.window_s <= 0.5))
    return "merge_window_s: must be in (0, 0.5] seconds";
  if (!(config.timeout_s > 0.0 && config.timeout_s <= 10.0))
    return "merge_timeout_s: must be in (0, 10] seconds";
  return std::nullopt;
}

std::optional<std::string> extrinsic_error(const Eigen::Isometry3d& extrinsic) {
  const Eigen::Matrix4d& m = extrinsic.matrix();
  if (!m.allFinite()) return "is not finite";
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9)
    return "last row is not 0 0 0 1";
  const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      r.determinant() < 0)
    return "rotation is not orthonormal with determinant +1";
  return std::nullopt;
}

std::uint64_t ScanMergerCounters::rejected() const {
  std::uint64_t n = 0;
  for (const SensorMergeCounters& s : sensors) n += s.out_of_order + s.late;
  return n;
}

std::uint64_t ScanMergerCounters::missing() const {
  std::uint64_t n = 0;
  for (const SensorMergeCounters& s : sensors) n += s.missing;
  return n;
}

ScanMerger::ScanMerger(std::vector<Eigen::Isometry3d> extrinsics, ScanMergerConfig config)
    : extrinsics_(std::move(extrinsics)),
      window_ns_(std::llround(config.window_s * 1e9)),
      timeout_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(config.timeout_s))) {
  if (extrinsics_.empty()) throw std::invalid_argument("scan merger: no sensors");
  if (const auto why = scan_merger_config_error(config))
    throw std::invalid_argument("scan merger: " + *why);
  for (std::size_t i = 0; i < extrinsics_.size(); ++i)
    if (const auto why = extrinsic_error(extrinsics_[i]))
      throw std::invalid_argument("scan merger: extrinsic of sensor " + std::to_string(i) + " " +
                                  *why);
  slots_.resize(extrinsics_.size());
  last_stamp_.resize(extrinsics_.size());
  floor_.resize(extrinsics_.size());
  counters_.sensors.resize(extrinsics_.size());
}

std::vector<Frame> ScanMerger::add(std::size_t sensor, Frame scan) {
  if (sensor >= extrinsics_.size())
    throw std::out_of_range("scan merger: sensor " + std::to_string(sensor) + " of " +
                            std::to_string(extrinsics_.size()));
  SensorMergeCounters& counters = counters_.sensors[sensor];
  const Stamp stamp = scan.stamp;
  if (last_stamp_[sensor] && !(*last_stamp_[sensor] < stamp)) {
    ++counters.out_of_order;
    return {};
  }
  if (floor_[sensor] && !(*floor_[sensor] < stamp)) {
    ++counters.late;
    return {};
  }
  std::vector<Frame> out;
  if (arrived_ > 0) {
    if (newest_.nanoseconds - stamp.nanoseconds > window_ns_) {
      ++counters.late;
      return {};
    }
    const bool beyond_window = stamp.nanoseconds - earliest_.nanoseconds > window_ns_;
    if (beyond_window || slots_[sensor]) {
      out.push_back(emit(stamp));
      // A second scan of a sensor within the window may be older than another sensor's scan
      // of the frame just emitted.
      if (!(*floor_[sensor] < stamp)) {
        ++counters.late;
        return out;
      }
    }
  }
  last_stamp_[sensor] = stamp;
  ++counters.scans;
  if (arrived_ == 0) {
    earliest_ = newest_ = stamp;
    first_arrival_ = scan.arrival;
  } else {
    if (stamp < earliest_) earliest_ = stamp;
    if (newest_ < stamp) newest_ = stamp;
    if (scan.arrival < first_arrival_) first_arrival_ = scan.arrival;
  }
  slots_[sensor] = std::move(scan);
  ++arrived_;
  if (arrived_ == slots_.size()) out.push_back(emit(std::nullopt));
  return out;
}

std::vector<Frame> ScanMerger::expire(Clock::time_point now) {
  if (arrived_ == 0 || now - first_arrival_ < timeout_) return {};
  return {emit(std::nullopt)};
}

std::vector<Frame> ScanMerger::flush() {
  if (arrived_ == 0) return {};
  return {emit(std::nullopt)};
}

std::vector<Frame> ScanMerger::restart() {
  std::vector<Frame> out = flush();
  for (auto& s : last_stamp_) s.reset();
  for (auto& s : floor_) s.reset();
  return out;
}

Frame ScanMerger::emit(std::optional<Stamp> next) {
  Frame merged;
  merged.stamp = earliest_;
  merged.arrival = first_arrival_;
  merged.sequence = counters_.frames;
  bool any_times = false, all_intensities = true;
  std::size_t total = 0;
  for (const auto& slot : slots_) {
    if (!slot) continue;
    total += slot->cloud.size();
    any_times = any_times || slot->cloud.has_times();
    all_intensities = all_intensities && slot->cloud.has_intensities();
  }
  PointCloud& cloud = merged.cloud;
  cloud.points.reserve(total);
  if (any_times) cloud.times.reserve(total);
  if (all_intensities) cloud.intensities.reserve(total);
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    if (!slots_[i]) {
      ++counters_.sensors[i].missing;
      continue;
    }
    const PointCloud& scan = slots_[i]->cloud;
    const Eigen::Isometry3d& extrinsic = extrinsics_[i];
    for (const Eigen::Vector3f& p : scan.points)
      cloud.points.push_back((extrinsic * p.cast<double>()).cast<float>());
    if (any_times) {
      // Seconds from the merged stamp to this scan's stamp (>= 0: the merged stamp is the
      // earliest).
      const double offset =
          static_cast<double>(slots_[i]->stamp.nanoseconds - earliest_.nanoseconds) * 1e-9;
      if (scan.has_times()) {
        for (const float t : scan.times)
          cloud.times.push_back(static_cast<float>(static_cast<double>(t) + offset));
      } else {
        cloud.times.insert(cloud.times.end(), scan.size(), static_cast<float>(offset));
      }
    }
    if (all_intensities)
      cloud.intensities.insert(cloud.intensities.end(), scan.intensities.begin(),
                               scan.intensities.end());
  }
  ++counters_.frames;
  if (arrived_ < slots_.size()) ++counters_.incomplete_frames;
  // Later scans must be newer than every scan of this frame; a sensor missing from it must
  // also be beyond its window (its scan came too late), or at the scan that opens the next.
  const Stamp window_end{earliest_.nanoseconds + window_ns_};
  const Stamp missing_floor =
      next && *next < window_end ? Stamp{next->nanoseconds - 1} : window_end;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    Stamp floor = newest_;
    if (!slots_[i] && floor < missing_floor) floor = missing_floor;
    if (!floor_[i] || *floor_[i] < floor) floor_[i] = floor;
  }
  for (auto& slot : slots_) slot.reset();
  arrived_ = 0;
  return merged;
}

}  // namespace litamin2::daemon
