/// Forwarding of Fast DDS's log to spdlog (see participant_factory.hpp).

#include <spdlog/spdlog.h>

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

}  // namespace

void forward_fastdds_log_to_spdlog() {
  static std::once_flag once;
  std::call_once(once, [] {
    fdds::Log::ClearConsumers();
    fdds::Log::RegisterConsumer(std::make_unique<SpdlogConsumer>());
    fdds::Log::SetVerbosity(fdds::Log::Kind::Warning);
  });
}

}  // namespace litamin2::dds
