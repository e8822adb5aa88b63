#pragma once
/// The reader listener of a stream's opt-in zero-copy input (streams[].zero_copy_topic,
/// litamin2_zero_copy/PlainScan, same host only): takes each sample as a loan (with data-sharing, a
/// pointer into the writer's shared-memory pool: no copy into a reader history, no
/// deserialisation), converts it in place (dds::from_plain_scan), returns the loan, and hands
/// the scan to the stream's PointsListener, which applies the same checks (bad or empty scan,
/// stamp order) and counters as to a PointCloud2. A loaned sample the writer overwrote while
/// it was read (DataReader::is_sample_valid false after the conversion) is dropped and counted
/// as a bad message ("overwritten").

#include "litamin2/daemon/dds/points_listener.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

namespace litamin2::daemon {

class PlainScanListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  /// `points` (the stream's PointCloud2 listener) must outlive this listener.
  PlainScanListener(PointsListener& points, dds::CloudConversionOptions options);

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  void on_subscription_matched(
      eprosima::fastdds::dds::DataReader* reader,
      const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override;

 private:
  PointsListener& points_;
  const dds::CloudConversionOptions options_;
  /// Reused by every sample (its capacity stays).
  dds::CloudConversion conversion_;
};

}  // namespace litamin2::daemon
