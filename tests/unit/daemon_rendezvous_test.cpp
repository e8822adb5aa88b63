// Rendezvous hashing of streams over daemons: deterministic, balanced, and a change of the
// member set moves only the streams of the member that left or to the member that joined.

#include "litamin2/daemon/rendezvous.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

using litamin2::daemon::rendezvous_owner;
using litamin2::daemon::rendezvous_rank;
using litamin2::daemon::rendezvous_weight;

namespace {

std::vector<std::string> streams(int n) {
  std::vector<std::string> out;
  for (int i = 0; i < n; ++i) out.push_back("vehicle_" + std::to_string(i));
  return out;
}

std::map<std::string, std::string> assign(const std::vector<std::string>& members,
                                          const std::vector<std::string>& ids) {
  std::map<std::string, std::string> out;
  for (const auto& s : ids) out[s] = *rendezvous_owner(members, s);
  return out;
}

}  // namespace

TEST(Rendezvous, WeightDependsOnBothNamesAndIsStable) {
  EXPECT_EQ(rendezvous_weight("host-a", "car1"), rendezvous_weight("host-a", "car1"));
  EXPECT_NE(rendezvous_weight("host-a", "car1"), rendezvous_weight("host-b", "car1"));
  EXPECT_NE(rendezvous_weight("host-a", "car1"), rendezvous_weight("host-a", "car2"));
  // The separator keeps ("ab", "c") and ("a", "bc") apart.
  EXPECT_NE(rendezvous_weight("ab", "c"), rendezvous_weight("a", "bc"));
}

TEST(Rendezvous, OwnerIndependentOfOrderAndDuplicates) {
  const std::vector<std::string> a{"d1", "d2", "d3"}, b{"d3", "d1", "d2", "d1"};
  for (const auto& s : streams(200)) EXPECT_EQ(rendezvous_owner(a, s), rendezvous_owner(b, s));
  EXPECT_FALSE(rendezvous_owner({}, "car1").has_value());
  EXPECT_EQ(rendezvous_owner({"only"}, "car1").value(), "only");
}

TEST(Rendezvous, BalancedOverMembers) {
  const std::vector<std::string> members{"daemon-a", "daemon-b", "daemon-c", "daemon-d"};
  const auto ids = streams(4000);
  std::map<std::string, int> count;
  for (const auto& [stream, owner] : assign(members, ids)) ++count[owner];
  ASSERT_EQ(count.size(), members.size());
  // 1000 expected each; binomial sigma ~27: 10 % is more than 3.5 sigma.
  for (const auto& [member, n] : count) {
    EXPECT_GT(n, 900) << member;
    EXPECT_LT(n, 1100) << member;
  }
}

TEST(Rendezvous, RemovingAMemberMovesOnlyItsStreams) {
  const std::vector<std::string> before{"d1", "d2", "d3"}, after{"d1", "d3"};
  const auto ids = streams(1000);
  const auto a = assign(before, ids), b = assign(after, ids);
  int moved = 0;
  for (const auto& s : ids) {
    if (a.at(s) != "d2") {
      EXPECT_EQ(a.at(s), b.at(s)) << s;
    } else {
      ++moved;
      EXPECT_NE(b.at(s), "d2");
    }
  }
  EXPECT_GT(moved, 0);
}

TEST(Rendezvous, AddingAMemberMovesStreamsOnlyToIt) {
  const std::vector<std::string> before{"d1", "d2"}, after{"d1", "d2", "d3"};
  const auto ids = streams(900);
  const auto a = assign(before, ids), b = assign(after, ids);
  int moved = 0;
  for (const auto& s : ids)
    if (a.at(s) != b.at(s)) {
      EXPECT_EQ(b.at(s), "d3") << s;
      ++moved;
    }
  // About a third of the streams move to the new member.
  EXPECT_GT(moved, 240);
  EXPECT_LT(moved, 360);
}

TEST(Rendezvous, RanksFollowTheWeightsAndTheOwnerHasRankZero) {
  const std::vector<std::string> members{"d1", "d2", "d3", "d4"};
  for (const auto& s : streams(200)) {
    std::vector<std::pair<std::uint64_t, std::string>> by_weight;
    for (const auto& m : members) by_weight.emplace_back(rendezvous_weight(m, s), m);
    std::sort(by_weight.begin(), by_weight.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t r = 0; r < by_weight.size(); ++r)
      EXPECT_EQ(rendezvous_rank(members, by_weight[r].second, s), r) << s;
    EXPECT_EQ(rendezvous_rank(members, *rendezvous_owner(members, s), s), 0u) << s;
  }
}

TEST(Rendezvous, RankOfAnAbsentMemberIsNoneAndDuplicatesCountOnce) {
  EXPECT_EQ(rendezvous_rank({"d1", "d2"}, "d3", "car"), std::nullopt);
  EXPECT_EQ(rendezvous_rank({}, "d1", "car"), std::nullopt);
  const std::vector<std::string> members{"d1", "d2"};
  const std::string last = rendezvous_rank(members, "d1", "car") == 1u ? "d1" : "d2";
  EXPECT_EQ(rendezvous_rank({"d1", "d2", "d1", "d2"}, last, "car"), 1u);
}

TEST(Rendezvous, WhenTheOwnerLeavesTheFirstStandbyOwns) {
  const std::vector<std::string> members{"d1", "d2", "d3"};
  for (const auto& s : streams(300)) {
    const std::string owner = *rendezvous_owner(members, s);
    std::string standby;
    for (const auto& m : members)
      if (rendezvous_rank(members, m, s) == 1u) standby = m;
    std::vector<std::string> rest;
    for (const auto& m : members)
      if (m != owner) rest.push_back(m);
    EXPECT_EQ(rendezvous_owner(rest, s), standby) << s;
  }
}
