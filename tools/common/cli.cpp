#include "common/cli.hpp"

#include "common/frame_range.hpp"

#include "litamin2/service/logging.hpp"
#include "litamin2/version.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace litamin2::tools {

void init_cli(CLI::App& app, const std::string& prog) {
  app.name(prog);
  app.set_version_flag("-V,--version", prog + " " + std::string(litamin2::version()),
                       "Print the version and exit");
}

CLI::Option* add_frames_option(CLI::App& app, std::string& spec, const std::string& what) {
  const CLI::Validator range(
      [](std::string& text) {
        std::string error;
        return parse_frame_range(text, &error) ? std::string() : error;
      },
      "A:B");
  return app.add_option("--frames", spec, "Range A:B (B exclusive), A: or :B of the " + what)
      ->check(range);
}

std::optional<int> parse_cli(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" of exit code 0 that CLI11 prints itself, on stdout.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    // CLI11 checks the required options before the unexpected arguments: name an unknown
    // option rather than a missing one it hid ("--frmaes 0:10 -o out seq" must not say
    // "INPUT is required").
    std::string message = e.what();
    if (dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
      const std::vector<std::string> extra = app.remaining();
      if (!extra.empty()) {
        message = "unexpected argument(s):";
        for (const std::string& arg : extra) message += " " + arg;
      }
    }
    print_error(app.get_name(), message);
    return kExitUsageError;
  }
  return std::nullopt;
}

void print_error(const std::string& prog, const std::string& message) {
  std::string line = message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  std::fprintf(stderr, "%s%s: error: %s\n", service::journal_prefix(3).c_str(), prog.c_str(),
               line.c_str());
}

int usage_error(const std::string& prog, const std::string& message) {
  print_error(prog, message);
  return kExitUsageError;
}

int runtime_error(const std::string& prog, const std::string& message) {
  print_error(prog, message);
  return kExitRuntimeError;
}

}  // namespace litamin2::tools
