#include "common/io/relations.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/io/testing_files.h"
#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using io_testing::WriteBytes;
using ::testing::HasSubstr;

TEST(RelationsTest, KeepsThePlanarPart) {
  TempDir dir;
  WriteBytes(dir / "r.relations",
             "# t1 t2 x y z roll pitch yaw\n"
             "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000 0.000000 0.000000 "
             "-1.682210\n"
             "\n"
             "1.5 2.5 1 2 9 0.1 0.2 0.5\n");
  const auto relations = ReadRelations(dir / "r.relations");
  ASSERT_EQ(relations.size(), 2u);
  EXPECT_EQ(relations[0].t1, 976052905.167303);
  EXPECT_EQ(relations[0].t2, 976052911.885496);
  EXPECT_EQ(relations[0].delta, Pose2(-0.056990, -0.128430, -1.682210));
  EXPECT_EQ(relations[1].delta, Pose2(1, 2, 0.5));
}

TEST(RelationsTest, MalformedLinesNameFileLineAndExpectation) {
  TempDir dir;
  WriteBytes(dir / "short.relations", "1 2 3 4 5 6 7 8\n1 2 3 4 5 6 7\n");
  try {
    ReadRelations(dir / "short.relations");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_THAT(e.what(), HasSubstr("short.relations:2: expected 8 fields"));
    EXPECT_THAT(e.what(), HasSubstr("found 7"));
  }
  WriteBytes(dir / "nan.relations", "1 2 3 4 5 6 7 nan\n");
  try {
    ReadRelations(dir / "nan.relations");
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1u);
    EXPECT_THAT(e.what(), HasSubstr("yaw is 'nan', expected a finite number"));
  }
}

TEST(RelationsRealDataTest, IntelRelations) {
  const auto path = std::filesystem::path(EVOSLAM_DATA_DIR) / "intel.relations";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  const auto relations = ReadRelations(path);
  EXPECT_EQ(relations.size(), 2984u);
  for (const Relation& r : relations) EXPECT_GT(r.t2, 0.0);
}

}  // namespace
}  // namespace evoslam
