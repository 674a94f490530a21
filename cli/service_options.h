#ifndef EVOSLAM_CLI_SERVICE_OPTIONS_H_
#define EVOSLAM_CLI_SERVICE_OPTIONS_H_

#include <CLI/CLI.hpp>

#include <string>

#include "common/service/service_client.h"

namespace evoslam::cli {

// How a command reaches a running coordinator.
struct ServiceArgs {
  std::string coordinator;  // empty: run embedded (job commands) or the default endpoint
  std::string server_key, client_key;
  double timeout = 30.0;
};

// Adds --coordinator, --curve-server-key, --curve-key and --timeout to `cmd`.
void AddServiceOptions(CLI::App* cmd, ServiceArgs& args, bool embedded_by_default);

// The client settings the arguments give (reads the key files; throws Error on a bad one).
ClientOptions ClientOptionsFrom(const ServiceArgs& args);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_SERVICE_OPTIONS_H_
