#include "litamin2/daemon/dds/plain_scan_listener.hpp"

#include "litamin2/dds/plain_scan_conversion.hpp"
#include "litamin2_zero_copy/msg/PlainScan.h"

#include <fastdds/dds/core/LoanableSequence.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include <chrono>

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

PlainScanListener::PlainScanListener(PointsListener& points, dds::CloudConversionOptions options)
    : points_(points), options_(options) {}

void PlainScanListener::on_data_available(fdds::DataReader* reader) {
  fdds::LoanableSequence<litamin2_zero_copy::msg::PlainScan> samples;
  fdds::SampleInfoSeq infos;
  while (reader->take(samples, infos, 1) == ReturnCode_t::RETCODE_OK) {
    for (fdds::LoanableCollection::size_type i = 0; i < samples.length(); ++i) {
      if (!infos[i].valid_data) continue;
      const auto arrival = std::chrono::steady_clock::now();
      dds::from_plain_scan(samples[i], options_, conversion_);
      const builtin_interfaces::msg::Time stamp = samples[i].stamp();
      if (!reader->is_sample_valid(&samples[i], &infos[i])) {
        // The writer reused the pool's slot: its pool (history depth + extra samples) was
        // smaller than what this reader had not taken yet.
        points_.reject("PlainScan", "overwritten",
                       "the writer reused the loaned sample while it was read");
        continue;
      }
      points_.accept(conversion_, stamp, arrival, "PlainScan");
    }
    reader->return_loan(samples, infos);
  }
}

void PlainScanListener::on_subscription_matched(fdds::DataReader* reader,
                                                const fdds::SubscriptionMatchedStatus& info) {
  points_.on_subscription_matched(reader, info);
}

}  // namespace litamin2::daemon
