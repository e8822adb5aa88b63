#pragma once
/// The level at which Fast DDS's SHM "buffer invalidated" warning reaches the log.
///
/// Fast DDS 2.9's shared-memory transport logs `Buffer is being invalidated, segment_size may be
/// insufficient` (category RTPS_TRANSPORT_SHM) whenever it reclaims a buffer, and the first
/// time in every process is an artefact of its start-up: `SharedMemTransport::init()` fills the
/// whole segment with one buffer and releases it, so the first real send reclaims that unused
/// buffer and logs the warning though nothing was lost (docs/deploy.md, "The SHM warning in the
/// logs"). Later ones are real: the sender's segment is full of buffers readers have not taken.
/// The filter demotes the first one in the process to debug and keeps every later one a
/// warning, with what it means. It never hides a warning of any other text or category.

#include <atomic>
#include <string>

namespace litamin2::dds {

class ShmWarningFilter {
 public:
  enum class Verdict {
    kNotShmInvalidation,  ///< another entry: log it as Fast DDS gave it
    kStartupArtefact,     ///< the process's first: debug
    kSegmentOverflow,     ///< every later one: a warning
  };

  /// Thread-safe: Fast DDS's log thread calls it, tests call it from theirs.
  Verdict classify(const std::string& category, const std::string& message);

  static bool is_shm_invalidation(const std::string& category, const std::string& message);

 private:
  std::atomic<bool> seen_{false};
};

}  // namespace litamin2::dds
