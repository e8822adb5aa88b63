#include "litamin2/dds/shm_warning_filter.hpp"

namespace litamin2::dds {

bool ShmWarningFilter::is_shm_invalidation(const std::string& category,
                                           const std::string& message) {
  return category == "RTPS_TRANSPORT_SHM" &&
         message.find("Buffer is being invalidated") != std::string::npos;
}

ShmWarningFilter::Verdict ShmWarningFilter::classify(const std::string& category,
                                                     const std::string& message) {
  if (!is_shm_invalidation(category, message)) return Verdict::kNotShmInvalidation;
  return seen_.exchange(true) ? Verdict::kSegmentOverflow : Verdict::kStartupArtefact;
}

}  // namespace litamin2::dds
