#pragma once
// The command-line convention of every litamin2 tool and of both services (docs/cli.md):
//   - exit 0 on success and after --help / -h or -V / --version (printed on stdout);
//   - exit 2 on a usage error: an unknown option, a bad or missing value, a wrong mix of options,
//     an invalid configuration file; one line "prog: error: ..." on stderr;
//   - exit 1 on a runtime error: unreadable or malformed input data, a failed write, a failed
//     service; also "prog: error: ..." on stderr.
// Error lines carry the journald priority prefix "<3>" only when stderr is the journal.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace litamin2::tools {

inline constexpr int kExitRuntimeError = 1;
inline constexpr int kExitUsageError = 2;

/// Names `app` after the program (`prog`, used in every error line) and adds -V,--version, which
/// prints "prog <version>". --help / -h is CLI11's own.
void init_cli(CLI::App& app, const std::string& prog);

/// Adds the shared --frames option: a half-open range "A:B" (B exclusive), "A:" or ":B" of the
/// input's frames (common/frame_range.hpp), checked as it is parsed; `what` names the frames in
/// the help text ("scans", "frames of every sequence").
CLI::Option* add_frames_option(CLI::App& app, std::string& spec, const std::string& what);

/// Parses the command line. Returns std::nullopt when the program should go on, otherwise its
/// exit status: 0 after --help or --version, kExitUsageError after a usage error (reported as
/// one "prog: error: ..." line).
std::optional<int> parse_cli(CLI::App& app, int argc, char** argv);

/// Writes "prog: error: message" (newlines folded into one line) on stderr.
void print_error(const std::string& prog, const std::string& message);

/// print_error, then kExitUsageError: for a usage error found after parsing.
int usage_error(const std::string& prog, const std::string& message);

/// print_error, then kExitRuntimeError.
int runtime_error(const std::string& prog, const std::string& message);

}  // namespace litamin2::tools
