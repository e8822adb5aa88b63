#pragma once
/// Rendezvous (highest-random-weight) hashing: which live daemon tracks a stream. Each
/// (member, stream) pair gets a pseudo-random weight; the stream's owner is the member with the
/// highest weight (ties, of probability ~2^-64, to the smaller member id). Every daemon that
/// sees the same live members computes the same owner without talking to the others, and when
/// a member leaves only its streams move (each to the member with its next-highest weight);
/// when one joins, only the streams it now wins move to it (Thaler and Ravishankar 1998).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace litamin2::daemon {

/// The weight of `member` for `stream`: FNV-1a 64 over member, a 0 byte and stream, then the
/// splitmix64 finaliser (FNV-1a alone mixes the last bytes poorly). Stable across hosts,
/// builds and releases: every daemon of a fleet must agree.
std::uint64_t rendezvous_weight(std::string_view member, std::string_view stream);

/// The owner of `stream` among `members` (any order; duplicates allowed); std::nullopt when
/// there is none.
std::optional<std::string> rendezvous_owner(const std::vector<std::string>& members,
                                            std::string_view stream);

/// The place of `member` in the order of `members` by weight for `stream` (highest first, ties
/// to the smaller id): 0 for the owner, 1 for the next (the first standby), ...; std::nullopt
/// when `member` is not among `members`. Hot standby (sharding.replicas k) tracks a stream on
/// the members of rank < k.
std::optional<std::size_t> rendezvous_rank(const std::vector<std::string>& members,
                                           std::string_view member, std::string_view stream);

}  // namespace litamin2::daemon
