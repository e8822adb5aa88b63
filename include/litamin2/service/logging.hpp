#pragma once
/// spdlog set up for a systemd service: one line per message on stderr, no colour, the level
/// name first. When stderr goes to the journal ($JOURNAL_STREAM is set, as systemd does for
/// StandardError=journal) each line starts with the syslog priority ("<3>" error ... "<7>"
/// debug) that journald turns into the entry's priority (SyslogLevelPrefix=yes is systemd's
/// default); on a terminal or a file there is no such prefix.

#include <array>
#include <string>

namespace litamin2::service {

/// The level names of the `log_level` keys, from most to least verbose.
inline constexpr std::array<const char*, 7> kLogLevels = {"trace", "debug",    "info", "warn",
                                                          "error", "critical", "off"};

/// Makes spdlog's default logger write to stderr as above, at `level` (trace, debug, info,
/// warn, error, critical, off; anything else throws std::invalid_argument).
void setup_logging(const std::string& level);

/// Changes the default logger's level at run time (a level name as above; anything else throws
/// std::invalid_argument and leaves the level as it was).
void set_log_level(const std::string& level);

/// The syslog priority of an spdlog level name ("info" -> 6).
int syslog_priority(const std::string& level);

/// Whether stderr is the journal's: $JOURNAL_STREAM is set and not empty.
bool stderr_is_journal();

/// The "<N>" priority prefix for a line written to stderr before logging is set up (e.g. a
/// config error), or "" when stderr_is_journal() is false.
std::string journal_prefix(int syslog_priority);

}  // namespace litamin2::service
