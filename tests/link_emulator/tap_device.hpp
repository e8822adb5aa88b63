// A TAP device (Ethernet frames, no packet-information header) owned by this process: created
// by opening /dev/net/tun with IFF_TAP | IFF_NO_PI, optionally inside another network
// namespace (setns(2) to it for the creation, then back: the device stays in the namespace it
// was created in and the file descriptor keeps working). Not persistent: the device disappears
// when the descriptor is closed. Needs CAP_NET_ADMIN (and CAP_SYS_ADMIN for setns).
#pragma once

#include <string>

namespace litamin2::testing {

class TapDevice {
 public:
  // Creates the device `name` (at most 15 characters) in the network namespace at
  // `netns_path` (e.g. /run/netns/NAME; empty: this process's namespace). The descriptor is
  // non-blocking. Throws std::runtime_error with the failing call and errno text.
  TapDevice(const std::string& name, const std::string& netns_path);
  ~TapDevice();
  TapDevice(const TapDevice&) = delete;
  TapDevice& operator=(const TapDevice&) = delete;

  int fd() const { return fd_; }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  int fd_ = -1;
};

}  // namespace litamin2::testing
