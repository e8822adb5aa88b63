#pragma once
/// The raw CDR path of received samples, hardened: a generated PubSubType whose deserialize()
/// never throws, refuses payloads above a size limit, and tells the reader that a sample could
/// not be read.
///
/// Why: fastcdr throws for malformed input (a bool byte that is neither 0 nor 1:
/// BadParamException; a sequence or string length beyond the payload, a truncated payload:
/// NotEnoughMemoryException), and the generated deserialize() does not catch it; Fast DDS calls
/// deserialize() inside take_next_sample() (and, for keyed types without a key hash, on its
/// receive thread), where an escaping exception ends the process (litamin2d died with SIGABRT on
/// a PointCloud2 whose is_dense byte was 2). When deserialize() returns false, Fast DDS 2.9's
/// take_next_sample() removes the sample and goes on to the next one, silently; so the failures
/// on the calling thread are kept for the listener (take_sample_failures) and counted on the
/// type (failures()).

#include <atomic>
#include <cstdint>
#include <exception>
#include <string>

#include <fastcdr/exceptions/Exception.h>
#include <fastdds/rtps/common/SerializedPayload.h>

namespace litamin2::dds {

/// Why a received sample could not be deserialised.
enum class SampleError {
  kNone = 0,
  /// The serialised payload is larger than the type's limit.
  kTooLarge,
  /// The payload is not a valid CDR encoding of the type (bad bool, truncated, a length beyond
  /// the payload, ...).
  kMalformed,
};

/// Short name of an error ("too_large", "malformed_cdr"), for counters and logs.
const char* to_string(SampleError error);

/// The deserialisations that failed on a thread.
struct SampleFailures {
  /// Samples dropped, by error.
  std::uint64_t too_large = 0;
  std::uint64_t malformed = 0;
  /// The last one's error and what fastcdr said.
  SampleError last_error = SampleError::kNone;
  std::string last_message;
  std::uint64_t count() const { return too_large + malformed; }
};

/// The CheckedType::deserialize() failures on the calling thread since the last call, and resets
/// them. A listener calls it at the start of on_data_available() (to forget failures of other
/// readers' deserialisation on this thread) and after each take_next_sample().
SampleFailures take_sample_failures();

/// Records a failed deserialisation on the calling thread (CheckedType's use).
void record_sample_failure(SampleError error, std::string message);

/// `PubSubType` (fastddsgen's) with a deserialize() that never throws and refuses payloads of
/// more than `max_payload_bytes` (0: no limit).
template <class PubSubType>
class CheckedType : public PubSubType {
 public:
  explicit CheckedType(std::uint32_t max_payload_bytes = 0)
      : max_payload_bytes_(max_payload_bytes) {}

  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    if (max_payload_bytes_ > 0 && payload->length > max_payload_bytes_) {
      return fail(SampleError::kTooLarge, std::to_string(payload->length) + " bytes > limit " +
                                              std::to_string(max_payload_bytes_));
    }
    try {
      if (PubSubType::deserialize(payload, data)) return true;
      return fail(SampleError::kMalformed, "not a valid encoding");
    } catch (const eprosima::fastcdr::exception::Exception& e) {
      return fail(SampleError::kMalformed, e.what());
    } catch (const std::exception& e) {
      return fail(SampleError::kMalformed, e.what());
    }
  }

  /// Samples that could not be deserialised so far.
  std::uint64_t failures() const { return failures_.load(); }

 private:
  bool fail(SampleError error, std::string message) {
    ++failures_;
    record_sample_failure(error, std::move(message));
    return false;
  }

  const std::uint32_t max_payload_bytes_;
  std::atomic<std::uint64_t> failures_{0};
};

}  // namespace litamin2::dds
