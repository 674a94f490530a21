#ifndef EVOSLAM_CLI_SERVICE_SESSION_H_
#define EVOSLAM_CLI_SERVICE_SESSION_H_

#include <zmq.hpp>

#include <memory>

#include "cli/embedded_service.h"
#include "cli/service_options.h"
#include "common/service/service_client.h"

namespace evoslam::cli {

// Where a job command sends its job: a coordinator and workers embedded in this process (no
// --coordinator; laid out as `layout` says), or the coordinator --coordinator names.
class ServiceSession {
 public:
  ServiceSession(const ServiceArgs& args, const EmbeddedLayout& layout);

  ServiceClient& client() { return *client_; }
  bool embedded() const { return embedded_ != nullptr; }

 private:
  std::unique_ptr<zmq::context_t> context_;
  std::unique_ptr<EmbeddedService> embedded_;
  std::unique_ptr<ServiceClient> client_;
};

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_SERVICE_SESSION_H_
