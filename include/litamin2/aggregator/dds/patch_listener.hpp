#pragma once
/// The reader listener of rt/litamin2/map_patches: converts each MapPatch to a keyframe
/// (dds::from_map_patch) and pushes it onto the PatchQueue; nothing else runs on the DDS
/// thread. Invalid patches (and samples the reader's dds::CheckedType could not deserialise)
/// are counted by reason and logged at most once per second; they never reach the store. Given
/// the partitions of the topic's writers, a patch whose stream id is not a partition of the
/// writer that sent it is rejected (dds::kStreamNotBound; dds/stream_partition.hpp).

#include "litamin2/aggregator/patch_queue.hpp"
#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/writer_partitions.hpp"
#include "litamin2/service/log_rate_limiter.hpp"
#include "litamin2/service/reason_counts.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <atomic>
#include <cstdint>

namespace litamin2::aggregator {

class PatchListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  /// `writers` (may be null: no stream binding check) must outlive the listener.
  explicit PatchListener(PatchQueue& queue, dds::PatchConversionOptions options = {},
                         const dds::WriterPartitions* writers = nullptr)
      : queue_(queue), options_(options), writers_partitions_(writers) {}

  /// Patches taken together are queued in their writers' source-timestamp order, this many at
  /// most at a time.
  static constexpr std::size_t kOrderWindow = 64;

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  void on_subscription_matched(
      eprosima::fastdds::dds::DataReader* reader,
      const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override;
  void on_sample_lost(eprosima::fastdds::dds::DataReader* reader,
                      const eprosima::fastdds::dds::SampleLostStatus& status) override;

  std::uint64_t received() const { return received_; }
  std::uint64_t rejected() const { return rejected_.total(); }
  /// rejected() by reason (dds::to_string of the PatchError or SampleError).
  std::map<std::string, std::uint64_t> rejected_by_reason() const { return rejected_.snapshot(); }
  std::uint64_t samples_lost() const { return samples_lost_; }
  int writers() const { return writers_; }
  /// CPU time of the DDS thread in the listener, seconds: taking samples (deserialisation) ...
  double take_cpu_s() const { return 1e-9 * static_cast<double>(take_cpu_ns_); }
  /// ... and converting them to keyframes (plus queueing).
  double convert_cpu_s() const { return 1e-9 * static_cast<double>(convert_cpu_ns_); }

 private:
  /// The stream id is a partition of the sample's writer (or there is no check); counts and
  /// logs the rejection otherwise.
  bool bound(const std::string& stream_id,
             const eprosima::fastrtps::rtps::InstanceHandle_t& writer);
  /// Counts `count` rejected patches of one reason and logs (rate-limited) `message`.
  void reject(const char* reason, std::uint64_t count, const std::string& message);

  PatchQueue& queue_;
  const dds::PatchConversionOptions options_;
  const dds::WriterPartitions* writers_partitions_;
  service::LogRateLimiter bad_patch_log_;
  std::atomic<std::uint64_t> received_{0};
  service::ReasonCounts rejected_;
  std::atomic<std::uint64_t> samples_lost_{0};
  std::atomic<int> writers_{0};
  std::atomic<std::uint64_t> take_cpu_ns_{0};
  std::atomic<std::uint64_t> convert_cpu_ns_{0};
};

}  // namespace litamin2::aggregator
