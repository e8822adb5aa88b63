/// Forwarding of Fast DDS's log to spdlog, and its shutdown before spdlog goes (see
/// participant_factory.hpp).

#include <spdlog/spdlog.h>

#include <cstdio>
#include <cstdlib>
#include <fastdds/dds/log/Log.hpp>
#include <memory>
#include <mutex>

#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/shm_warning_filter.hpp"

namespace litamin2::dds {

namespace {

namespace fdds = eprosima::fastdds::dds;

/// A Fast DDS log consumer writing to spdlog's default logger.
class SpdlogConsumer : public fdds::LogConsumer {
 public:
  void Consume(const fdds::Log::Entry& entry) override {
    const char* category = entry.context.category ? entry.context.category : "";
    switch (entry.kind) {
      case fdds::Log::Kind::Error:
        spdlog::error("fastdds [{}] {}", category, entry.message);
        break;
      case fdds::Log::Kind::Warning:
        switch (shm_filter().classify(category, entry.message)) {
          case ShmWarningFilter::Verdict::kNotShmInvalidation:
            spdlog::warn("fastdds [{}] {}", category, entry.message);
            break;
          case ShmWarningFilter::Verdict::kStartupArtefact:
            spdlog::debug(
                "fastdds [{}] {} (the SHM transport's start-up buffer reclaimed at the "
                "first send: nothing lost; docs/deploy.md)",
                category, entry.message);
            break;
          case ShmWarningFilter::Verdict::kSegmentOverflow:
            spdlog::warn(
                "fastdds [{}] {} (a sender's SHM segment is full of buffers not yet "
                "taken: readers lose those messages; raise its segment size, "
                "docs/deploy.md)",
                category, entry.message);
            break;
        }
        break;
      default:
        spdlog::debug("fastdds [{}] {}", category, entry.message);
        break;
    }
  }

 private:
  /// One per process, not per consumer: the start-up artefact happens once in a process.
  static ShmWarningFilter& shm_filter() {
    static ShmWarningFilter filter;
    return filter;
  }
};

/// After stop_fastdds_log: entries logged while the process ends go straight to stderr, with
/// nothing that static destruction could have destroyed.
class StderrConsumer : public fdds::LogConsumer {
 public:
  void Consume(const fdds::Log::Entry& entry) override {
    if (entry.kind == fdds::Log::Kind::Info) return;
    std::fprintf(stderr, "fastdds [%s] %s\n", entry.context.category ? entry.context.category : "",
                 entry.message.c_str());
  }
};

std::mutex& state_mutex() {
  static std::mutex mutex;
  return mutex;
}
bool forwarding = false;
bool stopped = false;

}  // namespace

void forward_fastdds_log_to_spdlog() {
  std::lock_guard lock(state_mutex());
  if (forwarding || stopped) return;
  // spdlog's registry is constructed before the exit handler is registered, so the handler
  // runs before the registry is destroyed (the order of static destruction and atexit handlers
  // is the reverse of their completion). The same holds for Fast DDS's log resources, which
  // ClearConsumers() constructs.
  spdlog::default_logger();
  fdds::Log::ClearConsumers();
  fdds::Log::RegisterConsumer(std::make_unique<SpdlogConsumer>());
  fdds::Log::SetVerbosity(fdds::Log::Kind::Warning);
  forwarding = true;
  std::atexit(stop_fastdds_log);
}

void stop_fastdds_log() {
  std::lock_guard lock(state_mutex());
  if (!forwarding || stopped) return;
  stopped = true;
  // Deliver what is queued while spdlog still exists, then make sure no entry reaches it:
  // ClearConsumers() waits for the log thread to leave the consumers, and the thread is joined.
  fdds::Log::Flush();
  spdlog::default_logger()->flush();
  fdds::Log::ClearConsumers();
  fdds::Log::RegisterConsumer(std::make_unique<StderrConsumer>());
  fdds::Log::KillThread();
}

}  // namespace litamin2::dds
