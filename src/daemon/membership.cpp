#include "litamin2/daemon/membership.hpp"

#include "litamin2/daemon/rendezvous.hpp"

#include <stdexcept>

namespace litamin2::daemon {

namespace {

constexpr std::string_view kPrefix = "litamin2d.member=";
constexpr std::size_t kMaxMemberId = 63;

bool is_alnum(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

}  // namespace

std::optional<std::string> member_id_error(std::string_view id) {
  if (id.empty()) return "empty";
  if (id.size() > kMaxMemberId)
    return "longer than " + std::to_string(kMaxMemberId) + " characters";
  if (!is_alnum(id.front())) return "does not start with a letter or a digit";
  for (const char c : id)
    if (!is_alnum(c) && c != '.' && c != '_' && c != '-')
      return "holds a character other than letters, digits, '.', '_' and '-'";
  return std::nullopt;
}

std::string member_user_data(std::string_view id) {
  return std::string(kPrefix) + std::string(id);
}

MemberAnnouncement parse_member_user_data(std::string_view user_data) {
  MemberAnnouncement a;
  if (user_data.substr(0, kPrefix.size()) != kPrefix) return a;
  a.is_daemon = true;
  const std::string_view id = user_data.substr(kPrefix.size());
  if (const auto why = member_id_error(id))
    a.error = *why;
  else
    a.member = std::string(id);
  return a;
}

Membership::Membership(std::string self) : self_(std::move(self)) {
  if (const auto why = member_id_error(self_))
    throw std::invalid_argument("member id '" + self_ + "': " + *why);
}

bool Membership::discovered(const std::string& participant, std::string_view user_data) {
  const MemberAnnouncement a = parse_member_user_data(user_data);
  if (!a.is_daemon) return false;
  if (!a.member) {
    ++rejected_;
    return false;
  }
  if (*a.member == self_) {
    ++self_conflicts_;
    return false;
  }
  const auto it = participants_.find(participant);
  if (it != participants_.end()) {
    if (it->second == *a.member) return false;
    const bool changed = lost(participant);
    return discovered(participant, user_data) || changed;
  }
  participants_.emplace(participant, *a.member);
  if (++members_[*a.member] == 1) {
    ++epoch_;
    return true;
  }
  return false;
}

bool Membership::lost(const std::string& participant) {
  const auto it = participants_.find(participant);
  if (it == participants_.end()) return false;
  const std::string member = it->second;
  participants_.erase(it);
  if (--members_[member] > 0) return false;
  members_.erase(member);
  ++epoch_;
  return true;
}

std::vector<std::string> Membership::live() const {
  std::set<std::string> all{self_};
  for (const auto& [member, count] : members_) all.insert(member);
  return {all.begin(), all.end()};
}

bool Membership::is_live(const std::string& member) const {
  return member == self_ || members_.count(member) > 0;
}

std::string Membership::owner(std::string_view stream) const {
  return *rendezvous_owner(live(), stream);
}

std::size_t Membership::rank(std::string_view stream) const {
  return *rendezvous_rank(live(), self_, stream);  // self_ is always live
}

}  // namespace litamin2::daemon
