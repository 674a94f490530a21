#include "common/protocol/curve_keys.h"

#include <sys/stat.h>
#include <zmq.h>

#include <array>
#include <fstream>
#include <sstream>

#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::size_t kKeyLength = 40;

void CheckZ85Key(const std::string& key, const std::string& where) {
  static constexpr std::string_view kAlphabet =
      "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&<>()[]{}@%$#";
  if (key.size() != kKeyLength)
    throw Error(where + ": a CURVE key is 40 Z85 characters, got " + std::to_string(key.size()));
  for (const char c : key) {
    if (kAlphabet.find(c) == std::string_view::npos)
      throw Error(where + ": '" + std::string(1, c) + "' is not a Z85 character");
  }
}

void WriteFile(const std::filesystem::path& path, const std::string& text, mode_t mode) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw Error("cannot write " + path.string());
  // Narrow the permissions before the secret is written, so it is never readable by others.
  if (chmod(path.c_str(), mode) != 0) throw Error("cannot set the permissions of " + path.string());
  out << text << '\n';
  if (!out.flush()) throw Error("cannot write " + path.string());
}

}  // namespace

CurveKeyPair GenerateCurveKeyPair() {
  std::array<char, kKeyLength + 1> public_key{}, secret_key{};
  if (zmq_curve_keypair(public_key.data(), secret_key.data()) != 0)
    throw Error("cannot make a CURVE key pair: this ZeroMQ was built without CURVE support");
  return {public_key.data(), secret_key.data()};
}

std::string CurvePublicKey(const std::string& secret_key) {
  CheckZ85Key(secret_key, "secret key");
  std::array<char, kKeyLength + 1> public_key{};
  if (zmq_curve_public(public_key.data(), secret_key.c_str()) != 0)
    throw Error("cannot derive a CURVE public key: this ZeroMQ lacks CURVE support");
  return public_key.data();
}

void WriteCurveKeyPair(const CurveKeyPair& keys, const std::filesystem::path& dir,
                       const std::string& name, bool overwrite) {
  if (name.empty() || name.find('/') != std::string::npos)
    throw Error("key name '" + name + "' must be a plain file name");
  const std::filesystem::path secret = dir / (name + ".key");
  const std::filesystem::path public_key = dir / (name + ".pub");
  // Both are checked before either is written, so a refusal never leaves a mismatched pair.
  for (const auto& path : {secret, public_key}) {
    if (!overwrite && std::filesystem::exists(path))
      throw Error(path.string() + " already exists (use --force to replace it)");
  }
  std::filesystem::create_directories(dir);
  WriteFile(secret, keys.secret_key, S_IRUSR | S_IWUSR);
  WriteFile(public_key, keys.public_key, S_IRUSR | S_IWUSR | S_IRGRP | S_IROTH);
}

std::string ReadCurveKey(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read key file " + path.string());
  std::stringstream text;
  text << in.rdbuf();
  std::string key = text.str();
  if (!key.empty() && key.back() == '\n') key.pop_back();
  CheckZ85Key(key, path.string());
  return key;
}

std::set<std::string> ReadPublicKeys(const std::vector<std::filesystem::path>& paths) {
  std::set<std::string> keys;
  for (const auto& path : paths) {
    if (std::filesystem::is_directory(path)) {
      for (const auto& entry : std::filesystem::directory_iterator(path)) {
        if (entry.path().extension() == ".pub") keys.insert(ReadCurveKey(entry.path()));
      }
    } else {
      keys.insert(ReadCurveKey(path));
    }
  }
  if (keys.empty()) throw Error("no public key found in the key files given");
  return keys;
}

}  // namespace evoslam
