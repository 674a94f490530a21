#include "common/util/sha256.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

std::string Hex(const std::array<std::uint8_t, 32>& digest) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex;
  for (const std::uint8_t byte : digest) {
    hex += kDigits[byte >> 4];
    hex += kDigits[byte & 0x0F];
  }
  return hex;
}

// Bytes of every value, not only text, so that signedness mistakes would show.
std::string PatternBytes(std::size_t size) {
  std::string bytes(size, '\0');
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>((i * 31 + 7) % 256);
  return bytes;
}

void WriteFile(const std::filesystem::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  ASSERT_TRUE(out.good()) << path;
}

// FIPS 180-4 examples (NIST CSRC "Example Algorithms", SHA-256).
TEST(Sha256Test, NistEmptyMessage) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256Test, NistAbc) {
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256Test, Nist448Bits) {
  // 56 bytes: the length no longer fits after the 1 bit, so padding takes a second block.
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256Test, NistOneMillionA) {
  EXPECT_EQ(Sha256Hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256Test, LengthsAroundTheBlockAndPaddingBoundaries) {
  // Reference digests from an independent implementation (Python's hashlib).
  const std::vector<std::pair<std::size_t, std::string>> cases = {
      {55, "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318"},
      {56, "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a"},
      {63, "7d3e74a05d7db15bce4ad9ec0658ea98e3f06eeecf16b4c6fff2da457ddc2f34"},
      {64, "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb"},
      {65, "635361c48bb9eab14198e76ea8ab7f1a41685d6ad62aa9146d301d4f17eb0ae0"},
      {119, "31eba51c313a5c08226adf18d4a359cfdfd8d2e816b13f4af952f7ea6584dcfb"},
      {120, "2f3d335432c70b580af0e8e1b3674a7c020d683aa5f73aaaedfdc55af904c21c"},
      {128, "6836cf13bac400e9105071cd6af47084dfacad4e5e302c94bfed24e013afb73e"},
  };
  for (const auto& [size, expected] : cases) {
    EXPECT_EQ(Sha256Hex(std::string(size, 'a')), expected) << size << " bytes";
  }
}

TEST(Sha256Test, EveryByteValue) {
  EXPECT_EQ(Sha256Hex(PatternBytes(130)),
            "1c7c3b5eee94d4fa8b41754b89153e50491838d0d3e49b0273d6f12cae12e387");
}

TEST(Sha256Test, IncrementalUpdatesAtEverySplitMatchOneShot) {
  const std::string message = PatternBytes(130);
  const std::string one_shot = Sha256Hex(message);
  const std::string_view view(message);
  for (std::size_t split = 0; split <= message.size(); ++split) {
    Sha256 hasher;
    hasher.Update(view.substr(0, split));
    hasher.Update(view.substr(split));
    EXPECT_EQ(Hex(hasher.Finish()), one_shot) << "split at " << split;
  }
}

TEST(Sha256Test, ByteSpansAndManySmallUpdatesMatchOneShot) {
  const std::string message = PatternBytes(130);
  const auto* bytes = reinterpret_cast<const std::byte*>(message.data());
  for (std::size_t step = 1; step <= 70; ++step) {
    Sha256 hasher;
    for (std::size_t at = 0; at < message.size(); at += step) {
      hasher.Update(std::span<const std::byte>(bytes + at, std::min(step, message.size() - at)));
    }
    EXPECT_EQ(Hex(hasher.Finish()), Sha256Hex(message)) << "step " << step;
  }
}

TEST(Sha256Test, UpdateAfterFinishThrows) {
  Sha256 hasher;
  hasher.Update("abc");
  hasher.Finish();
  EXPECT_THROW(hasher.Update("more"), Error);
  EXPECT_THROW(hasher.Update(std::span<const std::byte>()), Error);
  EXPECT_THROW(hasher.Finish(), Error);
}

// An upload is hashed chunk by chunk as it arrives; its hex digest must be Sha256Hex's.
TEST(Sha256Test, FinishHexOfChunkedUpdatesIsTheOneShotHex) {
  const std::string message = PatternBytes(1000);
  Sha256 hasher;
  for (std::size_t at = 0; at < message.size(); at += 96) {
    hasher.Update(std::string_view(message).substr(at, 96));
  }
  EXPECT_EQ(hasher.FinishHex(), Sha256Hex(message));
  EXPECT_THROW(hasher.FinishHex(), Error);
}

TEST(Sha256Test, FileHashEqualsStringHash) {
  const TempDir dir;
  // Empty, one partial chunk, and more than one 64 KiB read chunk with a partial one at the end.
  for (const std::size_t size : {std::size_t{0}, std::size_t{130}, std::size_t{200001}}) {
    const std::string content = PatternBytes(size);
    const auto path = dir / ("data_" + std::to_string(size));
    WriteFile(path, content);
    EXPECT_EQ(Sha256HexOfFile(path), Sha256Hex(content)) << size << " bytes";
  }
}

TEST(Sha256Test, MissingFileThrowsNamingIt) {
  const TempDir dir;
  const auto path = dir / "no_such_dataset.clf";
  try {
    Sha256HexOfFile(path);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(Sha256Test, UnreadableFileThrowsNamingIt) {
  // A directory opens on Linux but fails on read.
  const TempDir dir;
  try {
    Sha256HexOfFile(dir.path());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir.path().string()), std::string::npos) << e.what();
  }
}

TEST(IsSha256HexTest, AcceptsDigests) {
  EXPECT_TRUE(IsSha256Hex(Sha256Hex("abc")));
  EXPECT_TRUE(IsSha256Hex(std::string(64, '0')));
  EXPECT_TRUE(IsSha256Hex("0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef"));
}

TEST(IsSha256HexTest, RejectsEverythingElse) {
  const std::string good = Sha256Hex("abc");
  EXPECT_FALSE(IsSha256Hex(""));
  EXPECT_FALSE(IsSha256Hex(good.substr(0, 63)));
  EXPECT_FALSE(IsSha256Hex(good + "0"));
  for (const char bad : {'A', 'F', 'g', 'z', ' ', '-', '/', '.', '\0'}) {
    std::string text = good;
    text[17] = bad;
    EXPECT_FALSE(IsSha256Hex(text)) << "with '" << bad << "'";
  }
}

}  // namespace
}  // namespace evoslam
