#include "common/service/dataset_files.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "common/util/error.h"
#include "common/util/sha256.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

proto::DatasetRef RefOf(const std::string& name, const std::string& content) {
  proto::DatasetRef ref;
  ref.set_name(name);
  ref.set_sha256(Sha256Hex(content));
  ref.set_size_bytes(content.size());
  return ref;
}

std::string Read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(DatasetFilesTest, KeepsADatasetUnderItsHashAndName) {
  TempDir dir;
  DatasetFiles files(dir / "cache");
  const std::string log = "FLASER 3 1 2 3 0 0 0 0 0 0 0 host 0\n";
  const proto::DatasetRef ref = RefOf("run.clf", log);
  EXPECT_FALSE(files.Find(ref));
  const auto path = files.Put(ref, log);
  EXPECT_EQ(path.filename(), "run.clf");
  EXPECT_EQ(path.parent_path().filename(), ref.sha256());
  EXPECT_EQ(Read(path), log);
  EXPECT_EQ(files.Find(ref), path);
  // A second store of the same bytes finds them where they are.
  EXPECT_EQ(DatasetFiles(dir / "cache").Put(ref, log), path);
}

TEST(DatasetFilesTest, RefusesBytesThatDoNotMatchTheirReference) {
  TempDir dir;
  DatasetFiles files(dir.path());
  proto::DatasetRef ref = RefOf("a.clf", "the real bytes");
  EXPECT_THROW(files.Put(ref, "other bytes of a len"), Error);  // size differs
  EXPECT_THROW(files.Put(ref, "the fake bytes"), Error);        // same size, other hash
  EXPECT_FALSE(files.Find(ref));
  ref.set_sha256("../../etc/passwd");
  EXPECT_THROW(files.Put(ref, "the real bytes"), Error);
  EXPECT_FALSE(files.Find(ref));
}

TEST(DatasetFilesTest, NamesFromTheNetworkCannotLeaveTheCache) {
  EXPECT_EQ(SafeFileName("../../etc/passwd"), "passwd");
  EXPECT_EQ(SafeFileName("a b;c.clf"), "a_b_c.clf");
  EXPECT_EQ(SafeFileName(".."), "data");
  EXPECT_EQ(SafeFileName(""), "data");
  EXPECT_EQ(SafeFileName(std::string(300, 'x')).size(), 128u);
}

TEST(DatasetFilesTest, AMapYamlLivesBesideItsImage) {
  TempDir dir;
  DatasetFiles files(dir.path());
  const std::string yaml = "image: room.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
  const std::string pgm = "P2\n1 1\n255\n0\n";
  const auto yaml_ref = RefOf("room.yaml", yaml), image_ref = RefOf("room.pgm", pgm);
  EXPECT_THROW(files.MapWithImage(yaml_ref, image_ref), Error);  // not stored yet
  files.Put(yaml_ref, yaml);
  files.Put(image_ref, pgm);
  const auto path = files.MapWithImage(yaml_ref, image_ref);
  EXPECT_EQ(Read(path), yaml);
  EXPECT_EQ(Read(path.parent_path() / "room.pgm"), pgm);
}

}  // namespace
}  // namespace evoslam
