#ifndef EVOSLAM_COORDINATOR_METRICS_SERVER_H_
#define EVOSLAM_COORDINATOR_METRICS_SERVER_H_

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "coordinator/http_address.h"

namespace httplib {
class Server;
}

namespace evoslam {

// An HTTP server (cpp-httplib, on threads of its own) that answers GET /metrics with what
// `render` returns, as Prometheus's text format, and every other path with 404. `render` is
// called on the server's threads: it must be safe to call from any thread (Metrics::Render is).
class MetricsServer {
 public:
  // Listens on `address` at once, and throws Error naming it when it cannot (the port is taken,
  // the host is not one of this machine's).
  MetricsServer(const HttpAddress& address, std::function<std::string()> render);
  // Stops listening, and waits for a request being answered.
  ~MetricsServer();
  MetricsServer(const MetricsServer&) = delete;
  MetricsServer& operator=(const MetricsServer&) = delete;

  // Where it listens, a port 0 resolved.
  const HttpAddress& address() const { return address_; }
  // "http://HOST:PORT/metrics".
  std::string url() const { return "http://" + address_.ToString() + "/metrics"; }

 private:
  std::unique_ptr<httplib::Server> server_;
  HttpAddress address_;
  std::atomic<bool> listening_done_{false};
  std::jthread thread_;  // last: it stops before what it uses goes
};

}  // namespace evoslam

#endif  // EVOSLAM_COORDINATOR_METRICS_SERVER_H_
