#include "cli/service_options.h"

#include "common/util/error.h"

namespace evoslam::cli {

void AddServiceOptions(CLI::App* cmd, ServiceArgs& args, bool embedded_by_default) {
  cmd->add_option("--coordinator", args.coordinator,
                  embedded_by_default
                      ? "run on the coordinator at this endpoint instead of embedded"
                      : "the coordinator's client endpoint (default tcp://127.0.0.1:5555)");
  cmd->add_option("--curve-server-key", args.server_key,
                  "the coordinator's public key file (.pub), when it uses CURVE")
      ->check(CLI::ExistingFile);
  cmd->add_option("--curve-key", args.client_key, "this client's secret key file (.key)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--timeout", args.timeout, "seconds to wait for the coordinator's answer")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1e6));
}

ClientOptions ClientOptionsFrom(const ServiceArgs& args) {
  ClientOptions options;
  if (!args.coordinator.empty()) options.endpoint = args.coordinator;
  options.timeout_seconds = args.timeout;
  if (args.server_key.empty() != args.client_key.empty()) {
    throw Error("CURVE needs both --curve-server-key and --curve-key");
  }
  if (!args.server_key.empty()) {
    options.curve = LoadCurveClientKeys(args.server_key, args.client_key);
  }
  return options;
}

}  // namespace evoslam::cli
