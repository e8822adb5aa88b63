#pragma once
// litamin2-fleet-bench's restart measurement. The aggregator restarts as a new process, so the
// bench measures the restart in one: it runs itself again with --reopen-only, the child opens
// the final store as the aggregator does at start and reports the time to serving, its own
// peak RSS and a digest of the recovered graph; the parent compares the digest with the one of
// the graph it ended with (bit-identical recovery).

#include "litamin2/mapping/mapper.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace litamin2::bench {

/// FNV-1a over every keyframe (key, frame of its group's anchor, pose bits, in key order) and
/// every loop edge (ends, relative pose bits, in any order).
std::uint64_t graph_digest(const mapping::Mapper& mapper);

/// What the --reopen-only child reports.
struct RestartReport {
  double restart_s = 0.0;
  /// The child's peak RSS when the store was open and serving, MB.
  double peak_rss_mb = 0.0;
  std::size_t keyframes = 0;
  std::size_t loops = 0;
  std::uint64_t digest = 0;
};

/// Writes the report as JSON (the child's side).
void write_restart_report(const std::string& path, const RestartReport& report);

/// The malloc tuning the aggregator's systemd unit starts it with
/// (deploy/systemd/litamin2-aggregator.service): transparent huge pages for the heap, so that a
/// restart's ~2 GB of graph is not faulted in 4 KB at a time.
inline constexpr const char* kAggregatorGlibcTunables = "glibc.malloc.hugetlb=1";

/// Runs this executable (/proc/self/exe) with `arguments` plus `--reopen-only <report_path>`,
/// waits for it and reads its report. The child's environment is this one's, with
/// GLIBC_TUNABLES set to `glibc_tunables` (empty: as inherited). Throws std::runtime_error when
/// the child cannot start, fails or writes no valid report.
RestartReport run_restart_child(const std::vector<std::string>& arguments,
                                const std::string& report_path, const std::string& glibc_tunables);

}  // namespace litamin2::bench
