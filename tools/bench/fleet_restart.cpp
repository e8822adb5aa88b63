#include "fleet_restart.hpp"

#include <nlohmann/json.hpp>

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

extern char** environ;

namespace litamin2::bench {
namespace {

struct Fnv1a {
  std::uint64_t h = 14695981039346656037ull;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
  void text(const std::string& s) {
    const std::uint64_t n = s.size();
    bytes(&n, sizeof(n));
    bytes(s.data(), s.size());
  }
  void key(const KeyframeKey& k) {
    text(k.stream);
    bytes(&k.id, sizeof(k.id));
  }
  void pose(const Eigen::Isometry3d& t) { bytes(t.matrix().data(), 16 * sizeof(double)); }
};

}  // namespace

std::uint64_t graph_digest(const mapping::Mapper& mapper) {
  Fnv1a f;
  const mapping::KeyframeGraph& g = mapper.graph();
  for (const auto& [key, n] : g.by_key()) {
    const mapping::KeyframeNode& node = g.node(n);
    f.key(key);
    f.text(g.groups().at(g.groups().anchor_of(node.stream)).name);
    f.pose(node.pose);
  }
  // The loops in any order (the store recovers them in its own): a sum of one digest each.
  std::uint64_t loops = 0;
  for (const mapping::LoopEdge& e : mapper.loops()) {
    Fnv1a l;
    l.key(e.from);
    l.key(e.to);
    l.pose(e.relative);
    loops += l.h;
  }
  f.bytes(&loops, sizeof(loops));
  return f.h;
}

void write_restart_report(const std::string& path, const RestartReport& report) {
  const nlohmann::json j = {{"restart_s", report.restart_s},
                            {"peak_rss_mb", report.peak_rss_mb},
                            {"keyframes", report.keyframes},
                            {"loops", report.loops},
                            {"digest", report.digest}};
  std::ofstream out(path);
  out << j.dump() << "\n";
  if (!out) throw std::runtime_error("cannot write the restart report " + path);
}

RestartReport run_restart_child(const std::vector<std::string>& arguments,
                                const std::string& report_path, const std::string& glibc_tunables) {
  std::vector<std::string> args = arguments;
  args.push_back("--reopen-only");
  args.push_back(report_path);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // GLIBC_TUNABLES is read when the process starts: it is set in the child's environment.
  std::vector<std::string> variables;
  for (char** e = environ; *e != nullptr; ++e) {
    if (glibc_tunables.empty() || std::strncmp(*e, "GLIBC_TUNABLES=", 15) != 0)
      variables.emplace_back(*e);
  }
  if (!glibc_tunables.empty()) variables.push_back("GLIBC_TUNABLES=" + glibc_tunables);
  std::vector<char*> envp;
  for (std::string& v : variables) envp.push_back(v.data());
  envp.push_back(nullptr);
  pid_t pid = 0;
  const int spawned =
      posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), envp.data());
  if (spawned != 0) {
    throw std::runtime_error(std::string("cannot start the restart process: ") +
                             std::strerror(spawned));
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("waitpid on the restart process failed");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("the restart process failed (status " + std::to_string(status) + ")");
  }
  std::ifstream in(report_path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) {
    throw std::runtime_error("the restart process wrote no valid report " + report_path);
  }
  RestartReport r;
  r.restart_s = j.at("restart_s").get<double>();
  r.peak_rss_mb = j.at("peak_rss_mb").get<double>();
  r.keyframes = j.at("keyframes").get<std::size_t>();
  r.loops = j.at("loops").get<std::size_t>();
  r.digest = j.at("digest").get<std::uint64_t>();
  return r;
}

}  // namespace litamin2::bench
