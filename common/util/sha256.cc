#include "common/util/sha256.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <system_error>
#include <vector>

#include "common/util/error.h"

namespace evoslam {
namespace {

// FIPS 180-4 section 4.2.2: the first 32 bits of the fractional parts of the cube roots of the
// first 64 primes.
constexpr std::array<std::uint32_t, 64> kRoundConstants = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

// Section 5.3.3: the first 32 bits of the fractional parts of the square roots of the first 8
// primes.
constexpr std::array<std::uint32_t, 8> kInitialState = {
    0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};

constexpr std::size_t kBlockBytes = 64;
// Big enough that a file is read in few system calls.
constexpr std::size_t kFileChunkBytes = std::size_t{1} << 16;

std::uint32_t Rotr(std::uint32_t x, int n) { return (x >> n) | (x << (32 - n)); }

// The message is big-endian words (section 3.1), whatever the host's byte order.
std::uint32_t LoadBigEndian(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}

// Section 6.2.2 for `blocks` consecutive 64-byte blocks. Whole runs of blocks are hashed straight
// from the caller's bytes, so only a split block is ever copied.
void CompressBlocks(std::array<std::uint32_t, 8>& state, const unsigned char* data,
                    std::size_t blocks) {
  std::array<std::uint32_t, 64> w;
  for (; blocks > 0; --blocks, data += kBlockBytes) {
    for (std::size_t t = 0; t < 16; ++t) w[t] = LoadBigEndian(data + 4 * t);
    for (std::size_t t = 16; t < 64; ++t) {
      const std::uint32_t s0 = Rotr(w[t - 15], 7) ^ Rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
      const std::uint32_t s1 = Rotr(w[t - 2], 17) ^ Rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
      w[t] = w[t - 16] + s0 + w[t - 7] + s1;
    }
    std::uint32_t a = state[0], b = state[1], c = state[2], d = state[3];
    std::uint32_t e = state[4], f = state[5], g = state[6], h = state[7];
    for (std::size_t t = 0; t < 64; ++t) {
      const std::uint32_t big_sigma1 = Rotr(e, 6) ^ Rotr(e, 11) ^ Rotr(e, 25);
      const std::uint32_t choose = (e & f) ^ (~e & g);
      const std::uint32_t t1 = h + big_sigma1 + choose + kRoundConstants[t] + w[t];
      const std::uint32_t big_sigma0 = Rotr(a, 2) ^ Rotr(a, 13) ^ Rotr(a, 22);
      const std::uint32_t majority = (a & b) ^ (a & c) ^ (b & c);
      const std::uint32_t t2 = big_sigma0 + majority;
      h = g;
      g = f;
      f = e;
      e = d + t1;
      d = c;
      c = b;
      b = a;
      a = t1 + t2;
    }
    state[0] += a;
    state[1] += b;
    state[2] += c;
    state[3] += d;
    state[4] += e;
    state[5] += f;
    state[6] += g;
    state[7] += h;
  }
}

std::string ToHex(const std::array<std::uint8_t, 32>& digest) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * digest.size());
  for (const std::uint8_t byte : digest) {
    hex += kDigits[byte >> 4];
    hex += kDigits[byte & 0x0F];
  }
  return hex;
}

std::string ErrnoText(int error) { return std::generic_category().message(error); }

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

}  // namespace

Sha256::Sha256() : state_(kInitialState) {}

void Sha256::Update(std::span<const std::byte> data) {
  Consume(reinterpret_cast<const unsigned char*>(data.data()), data.size());
}

void Sha256::Update(std::string_view data) {
  Consume(reinterpret_cast<const unsigned char*>(data.data()), data.size());
}

void Sha256::Consume(const unsigned char* data, std::size_t size) {
  if (finished_) throw Error("Sha256: Update after Finish");
  // The length is only ever used modulo 2^64 bits (section 5.1.1 limits messages to less).
  message_bytes_ += size;
  if (block_size_ > 0) {
    const std::size_t take = std::min(size, kBlockBytes - block_size_);
    std::copy_n(data, take, block_.data() + block_size_);
    block_size_ += take;
    data += take;
    size -= take;
    if (block_size_ < kBlockBytes) return;
    CompressBlocks(state_, block_.data(), 1);
    block_size_ = 0;
  }
  const std::size_t whole = size / kBlockBytes;
  CompressBlocks(state_, data, whole);
  data += whole * kBlockBytes;
  size -= whole * kBlockBytes;
  std::copy_n(data, size, block_.data());
  block_size_ = size;
}

std::array<std::uint8_t, 32> Sha256::Finish() {
  if (finished_) throw Error("Sha256: Finish called twice");
  // Section 5.1.1: a 1 bit, zeros up to 56 bytes into a block, then the length in bits as a
  // big-endian 64-bit number; one or two blocks in all.
  const std::uint64_t message_bits = message_bytes_ * 8;
  std::array<unsigned char, 2 * kBlockBytes> tail{};
  std::copy_n(block_.data(), block_size_, tail.data());
  tail[block_size_] = 0x80;
  const std::size_t tail_size = block_size_ + 1 + 8 <= kBlockBytes ? kBlockBytes : 2 * kBlockBytes;
  for (std::size_t i = 0; i < 8; ++i) {
    tail[tail_size - 1 - i] = static_cast<unsigned char>(message_bits >> (8 * i));
  }
  CompressBlocks(state_, tail.data(), tail_size / kBlockBytes);
  finished_ = true;

  std::array<std::uint8_t, 32> digest;
  for (std::size_t i = 0; i < 8; ++i) {
    digest[4 * i] = static_cast<std::uint8_t>(state_[i] >> 24);
    digest[4 * i + 1] = static_cast<std::uint8_t>(state_[i] >> 16);
    digest[4 * i + 2] = static_cast<std::uint8_t>(state_[i] >> 8);
    digest[4 * i + 3] = static_cast<std::uint8_t>(state_[i]);
  }
  return digest;
}

std::string Sha256Hex(std::string_view data) {
  Sha256 hasher;
  hasher.Update(data);
  return ToHex(hasher.Finish());
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
  return ToHex(hasher.Finish());
}

bool IsSha256Hex(std::string_view text) {
  if (text.size() != 64) return false;
  for (const char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

}  // namespace evoslam
