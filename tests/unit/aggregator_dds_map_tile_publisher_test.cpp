// MapTilePublisher: each change gets the next revision; a tile changed within the period is
// held and goes out once, with its newest contents and revision; flush_all writes what is
// held; the counters add up; a gone tile goes out empty.

#include "litamin2/aggregator/dds/map_tile_publisher.hpp"
#include "litamin2/dds/map_tile_conversion.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace litamin2;
using namespace litamin2::aggregator;
using std::chrono::milliseconds;

namespace {

TileOutput tile(std::int32_t ix, std::int32_t iy, int distributions) {
  TileOutput t;
  t.key = {ix, iy};
  t.tile_size = 10.0;
  t.voxel_size = 1.0;
  t.anchor = "car_1";
  t.keyframes = distributions > 0 ? 2 : 0;
  for (int i = 0; i < distributions; ++i) {
    Distribution d;
    d.mean = Eigen::Vector3d(ix * 10.0 + 0.5 + 0.25 * i, iy * 10.0 + 0.5, 1.0);
    d.cov = Eigen::Vector3d(0.1, 0.1, 0.01).asDiagonal();
    d.count = 6;
    t.distributions.push_back(d);
  }
  return t;
}

struct Recorder {
  std::vector<litamin2::msg::MapTile> written;
  bool fail = false;
  MapTilePublisher::Write write() {
    return [this](litamin2::msg::MapTile& m) {
      if (fail) return false;
      written.push_back(m);
      return true;
    };
  }
};

/// A wall clock standing at `us` microseconds.
MapTilePublisher::RevisionClock fixed_clock(std::uint64_t us) {
  return [us] { return us; };
}

}  // namespace

TEST(MapTilePublisher, RevisionsFollowTheWallClockAndNeverRepeat) {
  // Two aggregators (a hot standby): the one that started first but publishes later must give
  // the higher revision, and one aggregator's revisions increase even while its clock stalls.
  Recorder out;
  std::uint64_t now_us = 5000;
  MapTilePublisher publisher(out.write(), 0.0, [&now_us] { return now_us; });
  const MapTilePublisher::Clock::time_point t0{};
  publisher.offer(tile(0, 0, 3), t0);
  publisher.offer(tile(0, 0, 4), t0 + milliseconds(1));  // same clock reading: +1
  now_us = 9000;
  publisher.offer(tile(0, 0, 5), t0 + milliseconds(2));  // the clock moved on: its reading
  now_us = 7000;
  publisher.offer(tile(0, 0, 6), t0 + milliseconds(3));  // the clock went back: still +1
  ASSERT_EQ(out.written.size(), 4u);
  EXPECT_EQ(out.written[0].revision(), 5000u);
  EXPECT_EQ(out.written[1].revision(), 5001u);
  EXPECT_EQ(out.written[2].revision(), 9000u);
  EXPECT_EQ(out.written[3].revision(), 9001u);
}

TEST(MapTilePublisher, HoldsChangesWithinThePeriodAndSendsTheNewestOnce) {
  Recorder out;
  MapTilePublisher publisher(out.write(), 1.0, fixed_clock(1000));
  const MapTilePublisher::Clock::time_point t0{};
  publisher.offer(tile(0, 0, 3), t0);
  publisher.offer(tile(1, 0, 2), t0);
  ASSERT_EQ(out.written.size(), 2u);
  EXPECT_EQ(out.written[0].revision(), 1000u);
  EXPECT_EQ(out.written[1].revision(), 1001u);
  publisher.offer(tile(0, 0, 4), t0 + milliseconds(100));
  publisher.offer(tile(0, 0, 5), t0 + milliseconds(200));  // replaces the held one
  EXPECT_EQ(out.written.size(), 2u);
  EXPECT_EQ(publisher.counters().held, 1u);
  publisher.flush_due(t0 + milliseconds(900));
  EXPECT_EQ(out.written.size(), 2u);
  publisher.flush_due(t0 + milliseconds(1000));
  ASSERT_EQ(out.written.size(), 3u);
  const litamin2::msg::MapTile& sent = out.written.back();
  EXPECT_EQ(sent.ix(), 0);
  EXPECT_EQ(sent.distributions().size(), 5u);  // the newest contents ...
  EXPECT_EQ(sent.revision(), 1003u);           // ... and revision
  const dds::TileConversion back = dds::from_map_tile(sent);
  EXPECT_TRUE(back.ok()) << back.message;
  EXPECT_EQ(back.tile.frame_id, "map");
  const MapTileCounters c = publisher.counters();
  EXPECT_EQ(c.published, 3u);
  EXPECT_EQ(c.deferred, 2u);
  EXPECT_EQ(c.folded, 1u);
  EXPECT_EQ(c.held, 0u);
}

TEST(MapTilePublisher, FlushAllWritesEveryHeldTile) {
  Recorder out;
  MapTilePublisher publisher(out.write(), 60.0, fixed_clock(1));
  const MapTilePublisher::Clock::time_point t0{};
  publisher.offer(tile(0, 0, 1), t0);
  publisher.offer(tile(2, -1, 1), t0);
  publisher.offer(tile(0, 0, 2), t0 + milliseconds(1));
  publisher.offer(tile(2, -1, 0), t0 + milliseconds(2));  // the tile has gone
  EXPECT_EQ(out.written.size(), 2u);
  publisher.flush_all();
  ASSERT_EQ(out.written.size(), 4u);
  EXPECT_EQ(publisher.counters().held, 0u);
  const litamin2::msg::MapTile& gone =
      out.written.back().ix() == 2 ? out.written.back() : out.written[2];
  EXPECT_TRUE(gone.distributions().empty());
  EXPECT_EQ(gone.keyframes(), 0u);
  EXPECT_TRUE(dds::from_map_tile(gone).ok());
}

TEST(MapTilePublisher, FailedWritesAreCounted) {
  Recorder out;
  out.fail = true;
  MapTilePublisher publisher(out.write(), 0.0, fixed_clock(1));
  publisher.offer(tile(0, 0, 1));
  const MapTileCounters c = publisher.counters();
  EXPECT_EQ(c.published, 0u);
  EXPECT_EQ(c.write_failures, 1u);
}
