#include "litamin2/aggregator/dds/patch_listener.hpp"

#include "litamin2/core/stopwatch.hpp"
#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/stream_partition.hpp"
#include "litamin2/msg/MapPatch.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <spdlog/fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace litamin2::aggregator {

namespace fdds = eprosima::fastdds::dds;

namespace {

std::uint64_t ns(double seconds) {
  return static_cast<std::uint64_t>(seconds * 1e9);
}

}  // namespace

void PatchListener::on_data_available(fdds::DataReader* reader) {
  litamin2::msg::MapPatch msg;
  fdds::SampleInfo info;
  // Fast DDS takes the available samples instance by instance (by key hash), not in the order
  // they were written; every stream has its own writer (dds/stream_partition.hpp), so patches of
  // streams starting together come in an arbitrary order. They are queued in their writers'
  // source-timestamp order, up to kOrderWindow at a time (the queue's back-pressure holds).
  std::vector<std::pair<eprosima::fastrtps::rtps::Time_t, Keyframe>> taken_patches;
  auto flush = [&] {
    std::stable_sort(taken_patches.begin(), taken_patches.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (auto& [stamp, keyframe] : taken_patches)
      if (!queue_.push(std::move(keyframe))) return false;  // shutting down
    taken_patches.clear();
    return true;
  };
  double t = thread_cpu_seconds();
  // The reader's type is a dds::CheckedType: Fast DDS drops (inside take_next_sample) a sample
  // it could not deserialise; count those.
  dds::take_sample_failures();
  for (;;) {
    const bool taken = reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK;
    const dds::SampleFailures failed = dds::take_sample_failures();
    const double taken_at = thread_cpu_seconds();
    take_cpu_ns_ += ns(taken_at - t);
    if (failed.count() > 0) {
      received_ += failed.count();
      reject(dds::to_string(dds::SampleError::kMalformed), failed.malformed, failed.last_message);
      reject(dds::to_string(dds::SampleError::kTooLarge), failed.too_large, failed.last_message);
    }
    if (!taken) break;
    t = taken_at;
    if (!info.valid_data) continue;
    ++received_;
    if (!bound(msg.stream_id(), info.publication_handle)) continue;
    dds::PatchConversion patch = dds::from_map_patch(msg, options_);
    const double converted_at = thread_cpu_seconds();
    convert_cpu_ns_ += ns(converted_at - t);
    t = converted_at;
    if (!patch.ok()) {
      reject(dds::to_string(patch.error), 1, patch.message);
      continue;
    }
    taken_patches.emplace_back(info.source_timestamp, std::move(patch.keyframe));
    if (taken_patches.size() >= kOrderWindow && !flush()) return;
  }
  flush();
}

bool PatchListener::bound(const std::string& stream_id,
                          const eprosima::fastrtps::rtps::InstanceHandle_t& writer) {
  if (!writers_partitions_) return true;
  const std::optional<std::vector<std::string>> partitions = writers_partitions_->find(writer);
  if (!partitions) {
    reject(dds::kStreamNotBound, 1,
           fmt::format("stream {}: its writer is unknown to discovery", stream_id));
    return false;
  }
  if (!dds::stream_bound(stream_id, *partitions)) {
    reject(dds::kStreamNotBound, 1,
           fmt::format("stream {} written by a writer in partition(s) [{}]", stream_id,
                       fmt::join(*partitions, ", ")));
    return false;
  }
  return true;
}

void PatchListener::reject(const char* reason, std::uint64_t count, const std::string& message) {
  if (count == 0) return;
  rejected_.add(reason, count);
  if (const auto suppressed = bad_patch_log_.allow())
    spdlog::warn("dropped a bad map patch ({}): {}{}", reason, message,
                 *suppressed ? fmt::format(" (and {} more since the last report)", *suppressed)
                             : std::string());
}

void PatchListener::on_subscription_matched(fdds::DataReader*,
                                            const fdds::SubscriptionMatchedStatus& info) {
  writers_ = info.current_count;
  spdlog::info("map patches: {} writer(s) matched", info.current_count);
}

void PatchListener::on_sample_lost(fdds::DataReader*, const fdds::SampleLostStatus& status) {
  samples_lost_ = static_cast<std::uint64_t>(status.total_count);
}

}  // namespace litamin2::aggregator
