#pragma once
// A temporary folder of the test process's own (TempDir()/<prefix><pid>), created on first use
// and removed with everything in it when the process exits: ctest runs each test in a process
// of its own, so the stores and files a test writes there do not pile up in /tmp.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace litamin2::testing {

inline std::filesystem::path process_temp_dir(const std::string& prefix) {
  struct RemovedAtExit {
    std::filesystem::path path;
    pid_t owner;
    ~RemovedAtExit() {
      if (::getpid() != owner) return;  // a forked child that exits normally leaves it alone
      std::error_code ignored;  // nothing to report at exit: a failed removal leaves a folder
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const RemovedAtExit dir{
      std::filesystem::path(::testing::TempDir()) / (prefix + std::to_string(::getpid())),
      ::getpid()};
  std::filesystem::create_directories(dir.path);
  return dir.path;
}

/// The path of an SQLite store `name` in process_temp_dir(prefix), with any earlier store of
/// that name (and its -wal, -shm files) removed.
inline std::string fresh_store_path(const std::string& prefix, const std::string& name) {
  const std::string path = (process_temp_dir(prefix) / name).string();
  for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(path + suffix);
  return path;
}

}  // namespace litamin2::testing
