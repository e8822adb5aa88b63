// The live set of daemons from participant discovery: joins and leaves by participant, a member
// live while any of its participants is, invalid and conflicting announcements counted.

#include "litamin2/daemon/membership.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

using litamin2::daemon::member_id_error;
using litamin2::daemon::member_user_data;
using litamin2::daemon::Membership;
using litamin2::daemon::parse_member_user_data;

TEST(MemberId, ValidAndInvalidIds) {
  EXPECT_FALSE(member_id_error("host-01.fleet_a").has_value());
  EXPECT_FALSE(member_id_error("7").has_value());
  EXPECT_TRUE(member_id_error("").has_value());
  EXPECT_TRUE(member_id_error("-host").has_value());
  EXPECT_TRUE(member_id_error("a b").has_value());
  EXPECT_TRUE(member_id_error("a/b").has_value());
  EXPECT_TRUE(member_id_error(std::string(64, 'a')).has_value());
  EXPECT_FALSE(member_id_error(std::string(63, 'a')).has_value());
  EXPECT_THROW(Membership("bad id"), std::invalid_argument);
}

TEST(MemberId, UserDataRoundTrip) {
  const auto a = parse_member_user_data(member_user_data("daemon2"));
  EXPECT_TRUE(a.is_daemon);
  EXPECT_EQ(a.member.value(), "daemon2");
  EXPECT_FALSE(parse_member_user_data("").is_daemon);
  EXPECT_FALSE(parse_member_user_data("ros2 node").is_daemon);
  const auto bad = parse_member_user_data("litamin2d.member=has space");
  EXPECT_TRUE(bad.is_daemon);
  EXPECT_FALSE(bad.member.has_value());
  EXPECT_FALSE(bad.error.empty());
}

TEST(Membership, SelfAloneOwnsEverything) {
  Membership m("a");
  EXPECT_EQ(m.live(), std::vector<std::string>{"a"});
  EXPECT_EQ(m.owner("car1"), "a");
  EXPECT_EQ(m.epoch(), 0u);
}

TEST(Membership, JoinAndLeaveChangeTheLiveSet) {
  Membership m("a");
  EXPECT_TRUE(m.discovered("guid-b", member_user_data("b")));
  EXPECT_EQ(m.live(), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(m.epoch(), 1u);
  // The same announcement again (Fast DDS re-reports on QoS changes) changes nothing.
  EXPECT_FALSE(m.discovered("guid-b", member_user_data("b")));
  EXPECT_EQ(m.epoch(), 1u);
  EXPECT_TRUE(m.lost("guid-b"));
  EXPECT_EQ(m.live(), std::vector<std::string>{"a"});
  EXPECT_EQ(m.epoch(), 2u);
  EXPECT_FALSE(m.lost("guid-b"));
  EXPECT_FALSE(m.lost("never-seen"));
}

TEST(Membership, MemberLiveWhileAnyParticipantAnnouncesIt) {
  // A daemon restarted on the same host: its new participant is discovered before the old
  // one's lease expires.
  Membership m("a");
  EXPECT_TRUE(m.discovered("old", member_user_data("b")));
  EXPECT_FALSE(m.discovered("new", member_user_data("b")));
  EXPECT_FALSE(m.lost("old"));
  EXPECT_TRUE(m.is_live("b"));
  EXPECT_TRUE(m.lost("new"));
  EXPECT_FALSE(m.is_live("b"));
}

TEST(Membership, OtherParticipantsAndBadAnnouncementsIgnoredAndCounted) {
  Membership m("a");
  EXPECT_FALSE(m.discovered("probe", ""));
  EXPECT_FALSE(m.discovered("aggregator", "something else"));
  EXPECT_EQ(m.rejected(), 0u);
  EXPECT_FALSE(m.discovered("x", "litamin2d.member=bad/id"));
  EXPECT_EQ(m.rejected(), 1u);
  EXPECT_FALSE(m.discovered("twin", member_user_data("a")));
  EXPECT_EQ(m.self_conflicts(), 1u);
  EXPECT_EQ(m.live(), std::vector<std::string>{"a"});
}

TEST(Membership, ParticipantChangingItsIdMoves) {
  Membership m("a");
  m.discovered("p", member_user_data("b"));
  EXPECT_TRUE(m.discovered("p", member_user_data("c")));
  EXPECT_EQ(m.live(), (std::vector<std::string>{"a", "c"}));
}

TEST(Membership, OwnerFollowsTheLiveSet) {
  Membership a("a"), b("b");
  a.discovered("pb", member_user_data("b"));
  b.discovered("pa", member_user_data("a"));
  // Both daemons agree on every stream's owner, and each stream has exactly one.
  int owned_by_a = 0;
  for (int i = 0; i < 100; ++i) {
    const std::string s = "car" + std::to_string(i);
    EXPECT_EQ(a.owner(s), b.owner(s));
    owned_by_a += a.owner(s) == "a";
  }
  EXPECT_GT(owned_by_a, 20);
  EXPECT_LT(owned_by_a, 80);
  // b dies: a owns everything.
  a.lost("pb");
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.owner("car" + std::to_string(i)), "a");
}
