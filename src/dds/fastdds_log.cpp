/// Forwarding of Fast DDS's log to spdlog (see participant_factory.hpp).

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <fastdds/dds/log/Log.hpp>
#include <memory>
#include <mutex>

#include "litamin2/dds/participant_factory.hpp"

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
        spdlog::warn("fastdds [{}] {}", category, entry.message);
        break;
      default:
        spdlog::debug("fastdds [{}] {}", category, entry.message);
        break;
    }
  }
};

/// At exit: delivers what Fast DDS's log thread still holds while spdlog is alive, then stops
/// that thread, so that it cannot call into spdlog's logger during static destruction (seen as a
/// segfault after main returned when a participant's teardown logged a warning).
void stop_fastdds_log() {
  fdds::Log::Flush();
  fdds::Log::KillThread();
}

}  // namespace

void forward_fastdds_log_to_spdlog() {
  static std::once_flag once;
  std::call_once(once, [] {
    // Both spdlog's registry and Fast DDS's log resources exist before the exit handler is
    // registered, so the handler runs before either is destroyed.
    spdlog::default_logger();
    fdds::Log::ClearConsumers();
    fdds::Log::RegisterConsumer(std::make_unique<SpdlogConsumer>());
    fdds::Log::SetVerbosity(fdds::Log::Kind::Warning);
    std::atexit(stop_fastdds_log);
  });
}

}  // namespace litamin2::dds
