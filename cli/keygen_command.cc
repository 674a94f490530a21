#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "common/protocol/curve_keys.h"

namespace evoslam::cli {
namespace {

struct KeygenArgs {
  std::string out = ".";
  std::string name;
  bool force = false;
};

void Run(const KeygenArgs& a) {
  const CurveKeyPair keys = GenerateCurveKeyPair();
  WriteCurveKeyPair(keys, a.out, a.name, a.force);
  const std::filesystem::path dir(a.out);
  std::printf("wrote %s (public) and %s (secret, owner-only)\npublic key: %s\n",
              (dir / (a.name + ".pub")).c_str(), (dir / (a.name + ".key")).c_str(),
              keys.public_key.c_str());
}

}  // namespace

void AddKeygenCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("keygen",
                                 "Make a CURVE key pair for the coordinator, a worker or a client");
  auto a = std::make_shared<KeygenArgs>();
  cmd->add_option("--name", a->name, "writes NAME.pub and NAME.key")->required();
  cmd->add_option("--out", a->out, "folder for the key files")
      ->type_name("DIR")
      ->capture_default_str();
  cmd->add_flag("--force", a->force, "replace existing key files");
  cmd->callback([a] { Run(*a); });
}

}  // namespace evoslam::cli
