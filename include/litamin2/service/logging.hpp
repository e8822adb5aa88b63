#pragma once
/// spdlog set up for a systemd service: one line per message on stderr, no colour, prefixed
/// with the syslog priority ("<3>" error ... "<7>" debug) that journald turns into the entry's
/// priority (SyslogLevelPrefix=yes is systemd's default), then the level name.

#include <array>
#include <string>

namespace litamin2::service {

/// The level names of the `log_level` keys, from most to least verbose.
inline constexpr std::array<const char*, 7> kLogLevels = {"trace", "debug",    "info", "warn",
                                                          "error", "critical", "off"};

/// Makes spdlog's default logger write to stderr as above, at `level` (trace, debug, info,
/// warn, error, critical, off; anything else throws std::invalid_argument).
void setup_logging(const std::string& level);

/// The syslog priority of an spdlog level name ("info" -> 6).
int syslog_priority(const std::string& level);

}  // namespace litamin2::service
