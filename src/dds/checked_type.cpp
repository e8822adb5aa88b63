#include "litamin2/dds/checked_type.hpp"

#include <utility>

namespace litamin2::dds {

namespace {
thread_local SampleFailures failures;
}  // namespace

const char* to_string(SampleError error) {
  switch (error) {
    case SampleError::kNone:
      return "none";
    case SampleError::kTooLarge:
      return "too_large";
    case SampleError::kMalformed:
      return "malformed_cdr";
  }
  return "unknown";
}

SampleFailures take_sample_failures() {
  return std::exchange(failures, SampleFailures{});
}

void record_sample_failure(SampleError error, std::string message) {
  ++(error == SampleError::kTooLarge ? failures.too_large : failures.malformed);
  failures.last_error = error;
  failures.last_message = std::move(message);
}

}  // namespace litamin2::dds
