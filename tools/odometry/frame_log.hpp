#pragma once
// frames.csv of an odometry run: one row per scan with what the tracker did with it (registered,
// inlier share, recovery, global search, map reset, re-grids, self-hits, time), so that a jump
// in the path can be traced to the frame and the mechanism that made it.

#include "litamin2/core/tracker.hpp"

#include <fstream>
#include <string>

namespace litamin2::tools {

class FrameLog {
 public:
  /// Creates (truncates) `path` and writes the header; throws std::runtime_error if it cannot.
  explicit FrameLog(const std::string& path);
  /// Scan `index` (file `file`), stamped `stamp_s` seconds, as the tracker returned it.
  void add(std::size_t index, const std::string& file, double stamp_s, const FrameResult& frame);
  /// Scan `index` could not be read and was skipped (--skip-bad-frames).
  void add_skipped(std::size_t index, const std::string& file, double stamp_s);

 private:
  std::ofstream out_;
};

}  // namespace litamin2::tools
