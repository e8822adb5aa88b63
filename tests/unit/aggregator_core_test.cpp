// The aggregator core with a distribution cache too small to hold anything but the latest
// keyframe (every verification re-reads its submap from the store) finds the same loops and
// poses, bit for bit, as with every keyframe in memory; reopened, it recovers the same graph
// from its tables.

#include "litamin2/aggregator/aggregator_core.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using namespace litamin2;
using namespace litamin2::aggregator;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;

namespace {

std::string fresh_store(const std::string& name) {
  const std::string dir = std::filesystem::temp_directory_path().string() + "/litamin2_core_test_" +
                          std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path + suffix);
  return path;
}

mapping::MapperConfig street_config() {
  mapping::MapperConfig config;
  config.place.min_travel_gap = 20.0;
  return config;
}

void feed(AggregatorCore& core, const std::vector<Keyframe>& keyframes) {
  for (std::size_t i = 0; i < keyframes.size(); i += 5) {
    std::vector<Keyframe> batch(
        keyframes.begin() + static_cast<std::ptrdiff_t>(i),
        keyframes.begin() + static_cast<std::ptrdiff_t>(std::min(i + 5, keyframes.size())));
    core.ingest(batch);
  }
}

void expect_same(const mapping::Mapper& a, const mapping::Mapper& b) {
  ASSERT_EQ(a.loops().size(), b.loops().size());
  for (std::size_t i = 0; i < a.loops().size(); ++i) {
    EXPECT_EQ(a.loops()[i].to, b.loops()[i].to);
    EXPECT_TRUE(a.loops()[i].relative.matrix() == b.loops()[i].relative.matrix()) << i;
  }
  const auto pa = a.poses(), pb = b.poses();
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i) {
    EXPECT_EQ(pa[i].key, pb[i].key);
    EXPECT_EQ(pa[i].frame, pb[i].frame);
    EXPECT_TRUE(pa[i].pose.matrix() == pb[i].pose.matrix()) << pa[i].key.id;
  }
}

}  // namespace

TEST(AggregatorCore, CacheEvictionAndReReadGiveIdenticalRegistrations) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  CoreOptions all_in_memory, tiny;
  all_in_memory.distribution_cache_bytes = 0;
  tiny.distribution_cache_bytes = 1;
  AggregatorCore a(fresh_store("a.db"), store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                   all_in_memory);
  AggregatorCore b(fresh_store("b.db"), store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                   tiny);
  feed(a, keyframes);
  feed(b, keyframes);
  EXPECT_GT(a.mapper().loops().size(), 5u);
  EXPECT_GT(b.mapper().cache().stats().misses, 20u) << "the cache was not exercised";
  EXPECT_LE(b.mapper().cache().stats().entries, 1u);
  expect_same(a.mapper(), b.mapper());
}

TEST(AggregatorCore, ReopenedRecoversTheSameGraphFromItsTables) {
  const auto truth = out_and_back();
  const auto a = drive("a", {truth.begin(), truth.begin() + 21}, 0.0, 1);
  const auto b = drive("b", {truth.begin() + 21, truth.end()}, 0.0, 2);
  const std::string path = fresh_store("reopen.db");
  std::vector<Keyframe> all = a;
  all.insert(all.end(), b.begin(), b.end());
  {
    AggregatorCore core(path, store::OpenMode::kCreateIfMissing, street_config());
    feed(core, all);
    ASSERT_FALSE(core.mapper().loops().empty());
    AggregatorCore reopened(path, store::OpenMode::kReadOnly, street_config());
    expect_same(core.mapper(), reopened.mapper());
    EXPECT_EQ(reopened.mapper().map_anchor(), core.mapper().map_anchor());
  }
}
