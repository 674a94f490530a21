#include "cli/service_session.h"

#include <spdlog/spdlog.h>

#include "common/util/counted.h"

namespace evoslam::cli {

ServiceSession::ServiceSession(const ServiceArgs& args, const EmbeddedLayout& layout) {
  if (args.coordinator.empty()) {
    spdlog::debug("embedded: {} of {}", Counted(layout.workers, "worker"),
                  Counted(layout.threads, "thread"));
    embedded_ = std::make_unique<EmbeddedService>(layout.workers, layout.threads);
    client_ = std::make_unique<ServiceClient>(embedded_->context(), embedded_->client_options());
  } else {
    context_ = std::make_unique<zmq::context_t>();
    client_ = std::make_unique<ServiceClient>(*context_, ClientOptionsFrom(args));
  }
}

}  // namespace evoslam::cli
