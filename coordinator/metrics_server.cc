#include "coordinator/metrics_server.h"

#include <httplib.h>
#include <sys/socket.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <utility>

#include "common/util/error.h"

namespace evoslam {

MetricsServer::MetricsServer(const HttpAddress& address, std::function<std::string()> render)
    : server_(std::make_unique<httplib::Server>()), address_(address) {
  // SO_REUSEADDR alone, not httplib's default SO_REUSEPORT, with which a second process could
  // bind the same port and take half of the scrapes.
  server_->set_socket_options([](::socket_t socket) {
    const int yes = 1;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  // Two threads are plenty for a scraper or two. (httplib owns the queue the factory makes.)
  server_->new_task_queue = [] { return new httplib::ThreadPool(2); };
  server_->Get("/metrics",
               [render = std::move(render)](const httplib::Request&, httplib::Response& response) {
                 response.set_content(render(), "text/plain; version=0.0.4; charset=utf-8");
               });
  errno = 0;
  bool bound = false;
  if (address_.port == 0) {
    const int port = server_->bind_to_any_port(address_.host);
    bound = port > 0;
    if (bound) address_.port = static_cast<std::uint16_t>(port);
  } else {
    bound = server_->bind_to_port(address_.host, address_.port);
  }
  if (!bound) {
    const int error = errno;
    throw Error("cannot serve metrics on " + address.ToString() + ": " +
                (error != 0 ? std::string(std::strerror(error))
                            : std::string("the host is unknown, or not this machine's")));
  }
  thread_ = std::jthread([this] {
    server_->listen_after_bind();
    listening_done_ = true;
  });
}

MetricsServer::~MetricsServer() {
  // A stop before the thread starts listening would be lost (httplib stops only a server that
  // runs), and the thread would listen for ever.
  while (!server_->is_running() && !listening_done_) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  server_->stop();
}

}  // namespace evoslam
