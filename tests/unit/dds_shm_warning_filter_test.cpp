// The SHM "buffer invalidated" warning: the process's first is the transport's start-up
// artefact (debug), every later one a real segment overflow (warning), anything else untouched.
#include "litamin2/dds/shm_warning_filter.hpp"

#include <gtest/gtest.h>

using litamin2::dds::ShmWarningFilter;

namespace {

const std::string kShm = "RTPS_TRANSPORT_SHM";
const std::string kText = "Buffer is being invalidated, segment_size may be insufficient";

TEST(ShmWarningFilter, OnlyTheFirstInvalidationIsTheStartupArtefact) {
  ShmWarningFilter filter;
  EXPECT_EQ(filter.classify(kShm, kText), ShmWarningFilter::Verdict::kStartupArtefact);
  EXPECT_EQ(filter.classify(kShm, kText), ShmWarningFilter::Verdict::kSegmentOverflow);
  EXPECT_EQ(filter.classify(kShm, kText), ShmWarningFilter::Verdict::kSegmentOverflow);
}

TEST(ShmWarningFilter, OtherEntriesAreNeverClassifiedAndDoNotUseUpTheFirst) {
  ShmWarningFilter filter;
  EXPECT_EQ(filter.classify(kShm, "Failed to create segment"),
            ShmWarningFilter::Verdict::kNotShmInvalidation);
  EXPECT_EQ(filter.classify("RTPS_TRANSPORT_UDP", kText),
            ShmWarningFilter::Verdict::kNotShmInvalidation);
  EXPECT_EQ(filter.classify("", ""), ShmWarningFilter::Verdict::kNotShmInvalidation);
  EXPECT_EQ(filter.classify(kShm, kText), ShmWarningFilter::Verdict::kStartupArtefact);
}

}  // namespace
