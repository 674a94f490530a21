#ifndef EVOSLAM_COMMON_UTIL_SHA256_H_
#define EVOSLAM_COMMON_UTIL_SHA256_H_

#include <sodium/crypto_hash_sha256.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace evoslam {

// SHA-256 (FIPS 180-4), computed by libsodium. Datasets are named by the SHA-256 of their bytes in
// the service protocol: the coordinator checks an upload against its name and workers cache
// datasets by it.
class Sha256 {
 public:
  Sha256();

  // Appends bytes to the message; any split of a message into calls gives the same hash.
  // Throws Error after Finish.
  void Update(std::span<const std::byte> data);
  void Update(std::string_view data);

  // The digest of everything given to Update. The hasher is spent afterwards: a further Update
  // or Finish throws Error.
  std::array<std::uint8_t, 32> Finish();
  // Finish's digest as 64 lowercase hex digits, the form the protocol names datasets by.
  std::string FinishHex();

 private:
  void Consume(const unsigned char* data, std::size_t size);

  crypto_hash_sha256_state state_;
  bool finished_ = false;
};

// The digest as 64 lowercase hex digits, the form the protocol names datasets by.
std::string Sha256Hex(std::string_view data);

// The digest of a file's bytes, read in chunks so a large log need not fit in memory. Throws
// Error, naming the path, when the file cannot be opened or read.
std::string Sha256HexOfFile(const std::filesystem::path& path);

// Whether `text` is exactly 64 lowercase hex digits, i.e. something Sha256Hex can return; lets a
// dataset name from the network be checked before it is used as a file name or a key.
bool IsSha256Hex(std::string_view text);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_SHA256_H_
