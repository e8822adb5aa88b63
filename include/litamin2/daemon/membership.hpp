#pragma once
/// Which litamin2d daemons are alive, as DDS discovery reports them (docs/deploy.md, "Several
/// daemon hosts"). Each daemon's participant carries "litamin2d.member=<member id>" in its
/// USER_DATA QoS; a participant that appears (DISCOVERED) joins its member, one whose lease
/// expires or that leaves (DROPPED, REMOVED) leaves it. A member is live while at least one
/// participant announces it; this daemon's own member is always live. Streams are assigned
/// over the live members by rendezvous hashing (rendezvous.hpp). Values from the network are
/// checked: an announcement with an invalid member id is rejected and counted, one of this
/// daemon's own id by another participant is counted as a conflict and not joined.
/// Not thread-safe: the main loop owns it.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace litamin2::daemon {

/// Why `id` is not a member id (std::nullopt when it is): 1 to 63 characters, ASCII letters,
/// digits, '.', '_' and '-', starting with a letter or a digit (host names are member ids).
std::optional<std::string> member_id_error(std::string_view id);

/// The USER_DATA of a daemon's participant: "litamin2d.member=<id>".
std::string member_user_data(std::string_view id);

/// What a participant's USER_DATA says.
struct MemberAnnouncement {
  /// It starts with "litamin2d.member=" (other participants are not daemons).
  bool is_daemon = false;
  /// The member id (when is_daemon and valid).
  std::optional<std::string> member;
  /// Why the member id was rejected (when is_daemon and not valid).
  std::string error;
};
MemberAnnouncement parse_member_user_data(std::string_view user_data);

class Membership {
 public:
  /// `self` must be a valid member id (std::invalid_argument otherwise).
  explicit Membership(std::string self);

  /// A participant (any unique key, e.g. its GUID) announced `user_data`. Returns true when the
  /// live set changed. Not a daemon: ignored; invalid id: rejected(); this daemon's own id from
  /// another participant: self_conflicts(). A participant announcing another id than before
  /// moves to it.
  bool discovered(const std::string& participant, std::string_view user_data);
  /// The participant left or its lease expired. Returns true when the live set changed.
  bool lost(const std::string& participant);

  const std::string& self() const { return self_; }
  /// The live members, sorted, this daemon's included.
  std::vector<std::string> live() const;
  bool is_live(const std::string& member) const;
  /// The live member that tracks `stream` (rendezvous_owner over live()).
  std::string owner(std::string_view stream) const;
  /// This daemon's place for `stream` among the live members (rendezvous_rank): 0 when it owns
  /// it, 1 when it is the first standby, ...
  std::size_t rank(std::string_view stream) const;
  /// Incremented at every change of the live set.
  std::uint64_t epoch() const { return epoch_; }
  std::uint64_t rejected() const { return rejected_; }
  std::uint64_t self_conflicts() const { return self_conflicts_; }

 private:
  std::string self_;
  /// Participant -> member it announced.
  std::map<std::string, std::string> participants_;
  /// Member -> number of participants announcing it (others than this daemon).
  std::map<std::string, int> members_;
  std::uint64_t epoch_ = 0;
  std::uint64_t rejected_ = 0;
  std::uint64_t self_conflicts_ = 0;
};

}  // namespace litamin2::daemon
