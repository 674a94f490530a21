#include "common/util/temp_dir.h"

#include <gtest/gtest.h>

#include <fstream>
#include <utility>

namespace evoslam {
namespace {

TEST(TempDirTest, CreatesAPrivateFolderAndRemovesItWithItsFiles) {
  std::filesystem::path where;
  {
    TempDir dir("evoslam-test");
    where = dir.path();
    ASSERT_TRUE(std::filesystem::is_directory(where));
    EXPECT_EQ(std::filesystem::status(where).permissions() & std::filesystem::perms::all,
              std::filesystem::perms::owner_all);
    std::ofstream(dir / "file") << "content";
  }
  EXPECT_FALSE(std::filesystem::exists(where));
}

TEST(TempDirTest, TwoFoldersNeverCoincideAndAMoveHandsOverOwnership) {
  TempDir a, b;
  EXPECT_NE(a.path(), b.path());
  const std::filesystem::path where = a.path();
  TempDir moved(std::move(a));
  EXPECT_EQ(moved.path(), where);
  b = std::move(moved);
  EXPECT_EQ(b.path(), where);
  EXPECT_TRUE(std::filesystem::is_directory(where));
}

}  // namespace
}  // namespace evoslam
