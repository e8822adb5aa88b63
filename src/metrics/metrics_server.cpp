#include "litamin2/metrics/metrics_server.hpp"

#include "litamin2/service/prometheus_text.hpp"

#include <httplib.h>
#include <sys/socket.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace litamin2::metrics {

MetricsServer::MetricsServer(const service::MetricsConfig& config,
                             const service::MetricsBoard& board,
                             std::chrono::milliseconds stale_after)
    : server_(std::make_unique<httplib::Server>()) {
  std::string why;
  const auto address = service::parse_listen_address(config.listen, &why);
  if (!address) throw std::runtime_error("metrics.listen: '" + config.listen + "': " + why);
  port_ = address->port;
  httplib::Server& s = *server_;
  // One thread: scrapes are rare and small; more would only compete with the tracking.
  s.new_task_queue = [] { return new httplib::ThreadPool(1); };
  s.set_read_timeout(std::chrono::seconds(2));
  s.set_write_timeout(std::chrono::seconds(2));
  s.set_keep_alive_max_count(10);
  // httplib's default sets SO_REUSEPORT, with which a second process binds the same port
  // without an error; only SO_REUSEADDR (a restart need not wait for TIME_WAIT).
  s.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  const service::MetricsBoard* b = &board;
  s.Get("/metrics", [b](const httplib::Request&, httplib::Response& res) {
    res.set_content(b->text(), service::kPrometheusContentType);
  });
  s.Get("/healthz", [b, stale_after](const httplib::Request&, httplib::Response& res) {
    const bool alive = b->alive(service::MetricsBoard::Clock::now(), stale_after);
    res.status = alive ? 200 : 503;
    res.set_content(alive ? "ok\n" : "main loop not turning\n", "text/plain");
  });
  s.Get("/readyz", [b](const httplib::Request&, httplib::Response& res) {
    const bool ready = b->ready();
    res.status = ready ? 200 : 503;
    res.set_content(ready ? "ready\n" : "not ready\n", "text/plain");
  });
  errno = 0;
  if (!s.bind_to_port(address->host, address->port)) {
    const int e = errno;
    throw std::runtime_error("metrics.listen: cannot listen on " + config.listen +
                             (e != 0 ? std::string(": ") + std::strerror(e) : std::string()));
  }
  thread_ = std::thread([this] {
    server_->listen_after_bind();
    finished_.store(true);
  });
}

MetricsServer::~MetricsServer() {
  // stop() does nothing before the thread's listen has begun: wait for it (or its end).
  while (!server_->is_running() && !finished_.load())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  server_->stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace litamin2::metrics
