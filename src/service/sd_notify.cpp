#include "litamin2/service/sd_notify.hpp"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace litamin2::service {

SdNotifier::SdNotifier(std::string path) : path_(std::move(path)) {
  if (path_.empty()) return;
  // Only absolute paths and abstract names are valid notification sockets.
  if ((path_[0] != '/' && path_[0] != '@') || path_.size() >= sizeof(sockaddr_un::sun_path)) {
    path_.clear();
    return;
  }
  fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) path_.clear();
}

SdNotifier SdNotifier::from_environment() {
  const char* path = std::getenv("NOTIFY_SOCKET");
  return SdNotifier(path ? std::string(path) : std::string());
}

SdNotifier::~SdNotifier() {
  if (fd_ >= 0) ::close(fd_);
}

SdNotifier::SdNotifier(SdNotifier&& other) noexcept
    : path_(std::move(other.path_)), fd_(other.fd_) {
  other.path_.clear();
  other.fd_ = -1;
}

SdNotifier& SdNotifier::operator=(SdNotifier&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = other.fd_;
    other.path_.clear();
    other.fd_ = -1;
  }
  return *this;
}

bool SdNotifier::notify(std::string_view message) const {
  if (!enabled() || fd_ < 0) return false;
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::memcpy(address.sun_path, path_.data(), path_.size());
  if (path_[0] == '@') address.sun_path[0] = '\0';
  const socklen_t length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + path_.size() +
                                                  (path_[0] == '@' ? 0 : 1));
  ssize_t sent;
  do {
    sent = ::sendto(fd_, message.data(), message.size(), MSG_NOSIGNAL,
                    reinterpret_cast<const sockaddr*>(&address), length);
  } while (sent < 0 && errno == EINTR);
  return sent == static_cast<ssize_t>(message.size());
}

bool SdNotifier::status(std::string_view text) const {
  std::string message = "STATUS=";
  message.append(text);
  for (char& c : message)
    if (c == '\n') c = ' ';
  return notify(message);
}

std::optional<std::chrono::microseconds> parse_watchdog_usec(const char* text) {
  if (!text || !*text) return std::nullopt;
  for (const char* p = text; *p; ++p)
    if (*p < '0' || *p > '9') return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(text, &end, 10);
  if (errno != 0 || *end != '\0' || value == 0) return std::nullopt;
  return std::chrono::microseconds(static_cast<std::chrono::microseconds::rep>(value));
}

std::optional<std::chrono::microseconds> watchdog_interval_from_environment() {
  const auto interval = parse_watchdog_usec(std::getenv("WATCHDOG_USEC"));
  if (!interval) return std::nullopt;
  if (const char* pid = std::getenv("WATCHDOG_PID"); pid && *pid) {
    char* end = nullptr;
    const long value = std::strtol(pid, &end, 10);
    if (*end != '\0' || value != static_cast<long>(::getpid())) return std::nullopt;
  }
  return interval;
}

WatchdogPinger::WatchdogPinger(const SdNotifier& notifier, std::chrono::microseconds interval)
    : notifier_(notifier), period_(interval / 2) {}

bool WatchdogPinger::tick(bool healthy, Clock::time_point now) {
  if (!enabled() || !healthy) return false;
  if (last_ && now - *last_ < period_) return false;
  last_ = now;
  if (!notifier_.watchdog()) return false;
  ++pings_;
  return true;
}

}  // namespace litamin2::service
