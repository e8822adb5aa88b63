#include "link_emulator/tap_device.hpp"

#include <fcntl.h>
#include <linux/if.h>
#include <linux/if_tun.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace litamin2::testing {

namespace {

std::runtime_error system_error(const std::string& what) {
  return std::runtime_error(what + ": " + std::strerror(errno));
}

// Opens the TAP device in the current network namespace.
int open_tap(const std::string& name) {
  if (name.empty() || name.size() >= IFNAMSIZ)
    throw std::runtime_error("TAP name '" + name + "': 1 to " + std::to_string(IFNAMSIZ - 1) +
                             " characters");
  const int fd = ::open("/dev/net/tun", O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw system_error("open /dev/net/tun");
  ifreq request{};
  request.ifr_flags = IFF_TAP | IFF_NO_PI;
  std::strncpy(request.ifr_name, name.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd, TUNSETIFF, &request) < 0) {
    const auto error = system_error("TUNSETIFF " + name);
    ::close(fd);
    throw error;
  }
  return fd;
}

// Enters the network namespace at `path` for its lifetime, then returns to the one before.
class NetnsScope {
 public:
  explicit NetnsScope(const std::string& path) {
    own_ = ::open("/proc/self/ns/net", O_RDONLY | O_CLOEXEC);
    if (own_ < 0) throw system_error("open /proc/self/ns/net");
    const int target = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (target < 0) {
      const auto error = system_error("open " + path);
      ::close(own_);
      throw error;
    }
    const int rc = ::setns(target, CLONE_NEWNET);
    const auto error = system_error("setns " + path);
    ::close(target);
    if (rc < 0) {
      ::close(own_);
      throw error;
    }
  }
  ~NetnsScope() {
    // Failing to return would leave this process in the other namespace: nothing can go on.
    if (::setns(own_, CLONE_NEWNET) < 0) std::abort();
    ::close(own_);
  }
  NetnsScope(const NetnsScope&) = delete;
  NetnsScope& operator=(const NetnsScope&) = delete;

 private:
  int own_ = -1;
};

}  // namespace

TapDevice::TapDevice(const std::string& name, const std::string& netns_path) : name_(name) {
  if (netns_path.empty()) {
    fd_ = open_tap(name);
  } else {
    NetnsScope scope(netns_path);
    fd_ = open_tap(name);
  }
}

TapDevice::~TapDevice() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace litamin2::testing
