#include "common/protocol/curve_keys.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

TEST(CurveKeysTest, PairsAreFreshAndThePublicKeyFollowsFromTheSecret) {
  const CurveKeyPair a = GenerateCurveKeyPair();
  const CurveKeyPair b = GenerateCurveKeyPair();
  EXPECT_EQ(a.public_key.size(), 40u);
  EXPECT_EQ(a.secret_key.size(), 40u);
  EXPECT_NE(a.secret_key, b.secret_key);
  EXPECT_EQ(CurvePublicKey(a.secret_key), a.public_key);
  EXPECT_NE(CurvePublicKey(a.secret_key), b.public_key);
  EXPECT_THROW(CurvePublicKey("too short"), Error);
  EXPECT_THROW(CurvePublicKey(std::string(40, ',')), Error);  // ',' is not Z85
}

TEST(CurveKeysTest, FilesRoundTripWithTheSecretReadableByTheOwnerOnly) {
  const evoslam::TempDir dir;
  const CurveKeyPair keys = GenerateCurveKeyPair();
  WriteCurveKeyPair(keys, dir.path() / "keys", "coordinator", false);
  EXPECT_EQ(ReadCurveKey(dir.path() / "keys" / "coordinator.pub"), keys.public_key);
  EXPECT_EQ(ReadCurveKey(dir.path() / "keys" / "coordinator.key"), keys.secret_key);
  struct stat secret {};
  ASSERT_EQ(stat((dir.path() / "keys" / "coordinator.key").c_str(), &secret), 0);
  EXPECT_EQ(secret.st_mode & 0777, 0600u);

  // An existing key is never overwritten by accident.
  EXPECT_THROW(WriteCurveKeyPair(GenerateCurveKeyPair(), dir.path() / "keys", "coordinator", false),
               Error);
  EXPECT_EQ(ReadCurveKey(dir.path() / "keys" / "coordinator.key"), keys.secret_key);
  EXPECT_THROW(WriteCurveKeyPair(keys, dir.path(), "../escape", false), Error);

  // A stray public key alone also stops the write, and no secret is left behind.
  std::ofstream(dir.path() / "lonely.pub") << keys.public_key << '\n';
  EXPECT_THROW(WriteCurveKeyPair(GenerateCurveKeyPair(), dir.path(), "lonely", false), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "lonely.key"));
}

TEST(CurveKeysTest, BadKeyFilesNameTheFile) {
  const evoslam::TempDir dir;
  std::ofstream(dir.path() / "bad.pub") << "not a key\n";
  try {
    ReadCurveKey(dir.path() / "bad.pub");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.pub"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ReadCurveKey(dir.path() / "missing.pub"), Error);
}

}  // namespace
}  // namespace evoslam
