// SIGHUP's reload: the log level applied at run time, every other changed key reported as
// needing a restart, an invalid file changing nothing.

#include "litamin2/config/config_reload.hpp"

#include "litamin2/config/daemon_config_yaml.hpp"
#include "litamin2/service/logging.hpp"

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

using namespace litamin2;
using config::changed_top_level_keys;
using config::ConfigReload;

namespace {

class ConfigReloadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One file per test and process: ctest runs this binary's tests in parallel processes, and
    // two of them writing one file made each read the other's config.
    path_ = testing::TempDir() + "config_reload_test_" +
            testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
            std::to_string(::getpid()) + ".yaml";
    service::setup_logging("info");
  }
  void TearDown() override { std::remove(path_.c_str()); }

  // A valid daemon config needs a stream source: discovery on, plus `text`.
  void write(const std::string& text) {
    std::ofstream(path_) << "discovery: {enabled: true}\n" << text;
  }

  ConfigReload make_reload() {
    return ConfigReload(
        path_, daemon::load_daemon_config(path_).log_level,
        [](const std::string& p) { return daemon::load_daemon_config(p).log_level; });
  }

  std::string path_;
};

}  // namespace

TEST(ConfigReloadKeys, ChangedAddedAndRemovedKeysAreFound) {
  const YAML::Node a =
      YAML::Load("threads: 1\nlog_level: info\ndds: {domain: 3}\nqueue_depth: 4\n");
  const YAML::Node b = YAML::Load("threads: 1\nlog_level: warn\ndds: {domain: 4}\ndiscovery: {}\n");
  EXPECT_EQ(changed_top_level_keys(a, b),
            (std::vector<std::string>{"dds", "discovery", "log_level", "queue_depth"}));
  EXPECT_TRUE(changed_top_level_keys(a, a).empty());
  EXPECT_EQ(changed_top_level_keys(YAML::Node(), YAML::Load("threads: 2\n")),
            std::vector<std::string>{"threads"});
}

TEST_F(ConfigReloadTest, LogLevelIsAppliedAndOtherChangesNeedARestart) {
  write("log_level: info\nthreads: 1\n");
  ConfigReload reload = make_reload();
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::info);

  write("log_level: warn\nthreads: 2\n");
  const ConfigReload::Outcome outcome = reload.reload();
  EXPECT_EQ(outcome.error, "");
  EXPECT_EQ(outcome.log_level, "warn");
  EXPECT_EQ(outcome.needs_restart, std::vector<std::string>{"threads"});
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::warn);

  // The ignored change is still reported on the next reload (it still differs from what runs);
  // the log level, applied, is not.
  write("log_level: warn\nthreads: 2\n");
  EXPECT_EQ(reload.reload().needs_restart, std::vector<std::string>{"threads"});
  write("log_level: debug\nthreads: 1\n");
  const ConfigReload::Outcome back = reload.reload();
  EXPECT_TRUE(back.needs_restart.empty());
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::debug);
}

TEST_F(ConfigReloadTest, InvalidFileChangesNothing) {
  write("log_level: info\n");
  ConfigReload reload = make_reload();
  write("log_level: error\nqueue_depth: 0\n");  // queue_depth out of range
  const ConfigReload::Outcome outcome = reload.reload();
  EXPECT_NE(outcome.error.find("queue_depth"), std::string::npos) << outcome.error;
  EXPECT_EQ(outcome.log_level, "info");
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::info);
  std::remove(path_.c_str());
  EXPECT_NE(reload.reload().error, "");  // a vanished file is an error too
  EXPECT_EQ(spdlog::default_logger()->level(), spdlog::level::info);
}
