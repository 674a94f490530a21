#include "common/util/sha256.h"

#include <sodium.h>

#include <cerrno>
#include <cstdio>
#include <memory>
#include <system_error>
#include <vector>

#include "common/util/error.h"

namespace evoslam {
namespace {

// Big enough that a file is read in few system calls.
constexpr std::size_t kFileChunkBytes = std::size_t{1} << 16;

// libsodium wants sodium_init before any other call; it is thread-safe and idempotent, and the
// static runs it once per process.
void InitSodium() {
  static const bool ready = sodium_init() >= 0;
  if (!ready) throw Error("Sha256: libsodium could not be initialised");
}

std::string ToHex(const std::array<std::uint8_t, 32>& digest) {
  std::array<char, 2 * 32 + 1> hex;  // lowercase digits and a terminating NUL
  sodium_bin2hex(hex.data(), hex.size(), digest.data(), digest.size());
  return std::string(hex.data(), 2 * digest.size());
}

std::string ErrnoText(int error) { return std::generic_category().message(error); }

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

}  // namespace

Sha256::Sha256() {
  InitSodium();
  crypto_hash_sha256_init(&state_);
}

void Sha256::Update(std::span<const std::byte> data) {
  Consume(reinterpret_cast<const unsigned char*>(data.data()), data.size());
}

void Sha256::Update(std::string_view data) {
  Consume(reinterpret_cast<const unsigned char*>(data.data()), data.size());
}

void Sha256::Consume(const unsigned char* data, std::size_t size) {
  if (finished_) throw Error("Sha256: Update after Finish");
  crypto_hash_sha256_update(&state_, data, size);
}

std::array<std::uint8_t, 32> Sha256::Finish() {
  if (finished_) throw Error("Sha256: Finish called twice");
  static_assert(crypto_hash_sha256_BYTES == 32);
  std::array<std::uint8_t, 32> digest;
  crypto_hash_sha256_final(&state_, digest.data());
  finished_ = true;
  return digest;
}

std::string Sha256::FinishHex() { return ToHex(Finish()); }

std::string Sha256Hex(std::string_view data) {
  Sha256 hasher;
  hasher.Update(data);
  return hasher.FinishHex();
}

std::string Sha256HexOfFile(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError(source, 0, "cannot open: " + ErrnoText(errno));
  Sha256 hasher;
  // On the heap: 64 KiB is a lot to ask of a worker thread's stack.
  std::vector<std::byte> chunk(kFileChunkBytes);
  while (true) {
    const std::size_t got = std::fread(chunk.data(), 1, chunk.size(), file.get());
    hasher.Update(std::span<const std::byte>(chunk.data(), got));
    if (got < chunk.size()) break;
  }
  if (std::ferror(file.get())) throw InputError(source, 0, "cannot read: " + ErrnoText(errno));
  return hasher.FinishHex();
}

bool IsSha256Hex(std::string_view text) {
  if (text.size() != 64) return false;
  for (const char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

}  // namespace evoslam
