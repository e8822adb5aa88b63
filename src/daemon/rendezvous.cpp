#include "litamin2/daemon/rendezvous.hpp"

#include <algorithm>

namespace litamin2::daemon {

namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;
constexpr std::uint64_t kFnvPrime = 1099511628211ull;

std::uint64_t fnv1a(std::uint64_t h, std::string_view bytes) {
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= kFnvPrime;
  }
  return h;
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

std::uint64_t rendezvous_weight(std::string_view member, std::string_view stream) {
  std::uint64_t h = fnv1a(kFnvOffset, member);
  h = fnv1a(h, std::string_view("\0", 1));
  h = fnv1a(h, stream);
  return splitmix64(h);
}

namespace {

/// `a` comes before `b` in the rendezvous order of `stream`.
bool ranks_before(std::string_view a, std::uint64_t weight_a, std::string_view b,
                  std::uint64_t weight_b) {
  return weight_a > weight_b || (weight_a == weight_b && a < b);
}

}  // namespace

std::optional<std::string> rendezvous_owner(const std::vector<std::string>& members,
                                            std::string_view stream) {
  const std::string* best = nullptr;
  std::uint64_t best_weight = 0;
  for (const std::string& m : members) {
    const std::uint64_t w = rendezvous_weight(m, stream);
    if (!best || ranks_before(m, w, *best, best_weight)) {
      best = &m;
      best_weight = w;
    }
  }
  if (!best) return std::nullopt;
  return *best;
}

std::optional<std::size_t> rendezvous_rank(const std::vector<std::string>& members,
                                           std::string_view member, std::string_view stream) {
  const std::uint64_t own = rendezvous_weight(member, stream);
  bool present = false;
  std::vector<std::string_view> before;  // distinct members ahead of `member`
  for (const std::string& m : members) {
    if (m == member) {
      present = true;
      continue;
    }
    if (ranks_before(m, rendezvous_weight(m, stream), member, own) &&
        std::find(before.begin(), before.end(), m) == before.end())
      before.push_back(m);
  }
  if (!present) return std::nullopt;
  return before.size();
}

}  // namespace litamin2::daemon
