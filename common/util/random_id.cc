#include "common/util/random_id.h"

#include <sodium.h>

#include <array>

#include "common/util/error.h"

namespace evoslam {

std::string RandomId(std::string_view prefix) {
  // Thread-safe and idempotent; the static runs it once per process.
  static const bool ready = sodium_init() >= 0;
  if (!ready) throw Error("libsodium cannot be initialised");
  std::array<unsigned char, 16> bytes{};
  randombytes_buf(bytes.data(), bytes.size());
  std::string id(prefix);
  for (const unsigned char b : bytes) {
    constexpr const char* kDigits = "0123456789abcdef";
    id += kDigits[b >> 4];
    id += kDigits[b & 15];
  }
  return id;
}

}  // namespace evoslam
