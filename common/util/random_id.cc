#include "common/util/random_id.h"

#include <sodium.h>

#include <vector>

#include "common/util/error.h"

namespace evoslam {

std::string RandomHexId(std::size_t bytes) {
  // sodium_init is thread-safe and idempotent; the static runs it once per process.
  static const bool ready = sodium_init() >= 0;
  if (!ready) throw Error("RandomHexId: libsodium could not be initialised");
  if (bytes == 0) return {};  // libsodium must not be handed an empty vector's null data()
  std::vector<unsigned char> random(bytes);
  randombytes_buf(random.data(), random.size());
  std::string hex(2 * bytes + 1, '\0');  // sodium_bin2hex writes a terminating NUL
  sodium_bin2hex(hex.data(), hex.size(), random.data(), random.size());
  hex.pop_back();
  return hex;
}

}  // namespace evoslam
