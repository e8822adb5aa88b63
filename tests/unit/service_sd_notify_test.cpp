// sd_notify protocol against a fake NOTIFY_SOCKET (a unix datagram socket bound by the test),
// path and abstract names, through libsystemd; WATCHDOG_USEC/WATCHDOG_PID and the watchdog
// pinger's cadence.

#include "litamin2/service/sd_notify.hpp"

#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

using namespace litamin2::service;
using namespace std::chrono_literals;

namespace {

/// A bound unix datagram socket that plays systemd's side.
class FakeSystemd {
 public:
  explicit FakeSystemd(const std::string& name) : name_(name) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, name.data(), name.size());
    socklen_t length = offsetof(sockaddr_un, sun_path) + name.size();
    if (name[0] == '@') {
      address.sun_path[0] = '\0';
    } else {
      ::unlink(name.c_str());
      length += 1;
    }
    bound_ = ::bind(fd_, reinterpret_cast<sockaddr*>(&address), length) == 0;
  }
  ~FakeSystemd() {
    ::close(fd_);
    if (name_[0] != '@') ::unlink(name_.c_str());
  }
  bool bound() const { return bound_; }

  /// The next datagram, or "" after `timeout`.
  std::string receive(std::chrono::milliseconds timeout = 2000ms) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return "";
    char buffer[4096];
    const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
    return n > 0 ? std::string(buffer, n) : std::string();
  }

 private:
  std::string name_;
  int fd_ = -1;
  bool bound_ = false;
};

std::string unique_name(const char* tag) {
  return std::string(tag) + std::to_string(::getpid()) + "_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

}  // namespace

/// Sets $NOTIFY_SOCKET for the scope (libsystemd reads it on every send).
class NotifySocketEnv {
 public:
  explicit NotifySocketEnv(const std::string& name) { ::setenv("NOTIFY_SOCKET", name.c_str(), 1); }
  ~NotifySocketEnv() { ::unsetenv("NOTIFY_SOCKET"); }
};

TEST(SdNotify, SendsToPathSocket) {
  const std::string path = ::testing::TempDir() + "/" + unique_name("notify");
  FakeSystemd systemd(path);
  ASSERT_TRUE(systemd.bound());
  NotifySocketEnv env(path);
  SdNotifier notifier = SdNotifier::from_environment();
  ASSERT_TRUE(notifier.enabled());
  EXPECT_EQ(notifier.socket(), path);
  EXPECT_TRUE(notifier.ready());
  EXPECT_EQ(systemd.receive(), "READY=1");
  EXPECT_TRUE(notifier.status("2 streams\nok"));
  EXPECT_EQ(systemd.receive(), "STATUS=2 streams ok");
  EXPECT_TRUE(notifier.watchdog());
  EXPECT_EQ(systemd.receive(), "WATCHDOG=1");
  EXPECT_TRUE(notifier.stopping());
  EXPECT_EQ(systemd.receive(), "STOPPING=1");
}

TEST(SdNotify, SendsToAbstractSocket) {
  const std::string name = "@" + unique_name("litamin2-notify-");
  FakeSystemd systemd(name);
  ASSERT_TRUE(systemd.bound());
  NotifySocketEnv env(name);
  SdNotifier notifier = SdNotifier::from_environment();
  ASSERT_TRUE(notifier.enabled());
  EXPECT_TRUE(notifier.ready());
  EXPECT_EQ(systemd.receive(), "READY=1");
}

TEST(SdNotify, DisabledWithoutSocket) {
  ::unsetenv("NOTIFY_SOCKET");
  SdNotifier notifier = SdNotifier::from_environment();
  EXPECT_FALSE(notifier.enabled());
  EXPECT_FALSE(notifier.ready());
  EXPECT_FALSE(SdNotifier().ready());
  // Not a socket address, and a socket nobody listens on: the sends fail, without throwing.
  {
    NotifySocketEnv env("relative/path");
    EXPECT_FALSE(SdNotifier::from_environment().ready());
  }
  NotifySocketEnv env("@litamin2-nobody-listens-" + std::to_string(::getpid()));
  SdNotifier nobody = SdNotifier::from_environment();
  EXPECT_TRUE(nobody.enabled());
  EXPECT_FALSE(nobody.ready());
}

TEST(SdNotify, WatchdogIntervalFromEnvironment) {
  ::setenv("WATCHDOG_USEC", "500000", 1);
  ::unsetenv("WATCHDOG_PID");
  EXPECT_EQ(watchdog_interval_from_environment(), std::chrono::microseconds(500000));
  ::setenv("WATCHDOG_PID", std::to_string(::getpid()).c_str(), 1);
  EXPECT_EQ(watchdog_interval_from_environment(), std::chrono::microseconds(500000));
  ::setenv("WATCHDOG_PID", std::to_string(::getpid() + 1).c_str(), 1);
  EXPECT_FALSE(watchdog_interval_from_environment());  // meant for another process
  ::unsetenv("WATCHDOG_PID");
  for (const char* invalid : {"", "0", "-5", "12abc", "99999999999999999999999"}) {
    ::setenv("WATCHDOG_USEC", invalid, 1);
    EXPECT_FALSE(watchdog_interval_from_environment()) << "WATCHDOG_USEC=" << invalid;
  }
  ::unsetenv("WATCHDOG_USEC");
  EXPECT_FALSE(watchdog_interval_from_environment());
}

TEST(WatchdogPinger, PingsAtHalfTheIntervalWhileHealthy) {
  const std::string name = "@" + unique_name("litamin2-wd-");
  FakeSystemd systemd(name);
  ASSERT_TRUE(systemd.bound());
  NotifySocketEnv env(name);
  SdNotifier notifier = SdNotifier::from_environment();
  WatchdogPinger pinger(notifier, std::chrono::microseconds(1000000));  // WatchdogSec=1
  ASSERT_TRUE(pinger.enabled());
  EXPECT_EQ(pinger.period(), 500ms);
  const auto t0 = WatchdogPinger::Clock::now();
  EXPECT_TRUE(pinger.tick(true, t0));  // first tick pings at once
  EXPECT_EQ(systemd.receive(), "WATCHDOG=1");
  EXPECT_FALSE(pinger.tick(true, t0 + 100ms));
  EXPECT_FALSE(pinger.tick(true, t0 + 499ms));
  EXPECT_TRUE(pinger.tick(true, t0 + 500ms));
  EXPECT_EQ(systemd.receive(), "WATCHDOG=1");
  // Unhealthy (a stalled stream): no pings, so systemd's watchdog fires.
  EXPECT_FALSE(pinger.tick(false, t0 + 1100ms));
  EXPECT_FALSE(pinger.tick(false, t0 + 1600ms));
  EXPECT_EQ(systemd.receive(100ms), "");
  EXPECT_TRUE(pinger.tick(true, t0 + 1700ms));
  EXPECT_EQ(systemd.receive(), "WATCHDOG=1");
  EXPECT_EQ(pinger.pings(), 3u);
}

TEST(WatchdogPinger, DisabledWithoutInterval) {
  NotifySocketEnv env("@litamin2-unused-" + std::to_string(::getpid()));
  SdNotifier notifier = SdNotifier::from_environment();
  WatchdogPinger pinger(notifier, std::chrono::microseconds(0));
  EXPECT_FALSE(pinger.enabled());
  EXPECT_FALSE(pinger.tick(true));
}
