#include "common/service/job_inputs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/sensor/dataset.h"
#include "common/service/dataset_files.h"
#include "common/util/error.h"
#include "common/util/sha256.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

using ::testing::HasSubstr;

proto::DatasetRef Keep(DatasetFiles& files, const std::string& name, const std::string& content) {
  proto::DatasetRef ref;
  ref.set_name(name);
  ref.set_sha256(Sha256Hex(content));
  ref.set_size_bytes(content.size());
  files.Put(ref, content);
  return ref;
}

Dataset ScansAt(std::initializer_list<double> timestamps) {
  Dataset log;
  log.source = "run.clf";
  for (const double t : timestamps) {
    LaserScan scan;
    scan.timestamp = t;
    log.scans.push_back(scan);
  }
  return log;
}

TEST(LoadJobRelationsTest, RelationsThatJoinNoTwoScansOfTheLogAreRefusedByName) {
  TempDir dir;
  DatasetFiles files(dir / "cache");
  const Dataset log = ScansAt({10.0, 10.5, 11.0});
  EXPECT_FALSE(LoadJobRelations(files, {}, log));

  // One of the two relations joins scans of the log: the other is left to the scoring to skip.
  const proto::DatasetRef some =
      Keep(files, "some.relations", "10.0 11.0 1 0 0 0 0 0\n10.5 20.0 1 0 0 0 0 0\n");
  const auto loaded = LoadJobRelations(files, some, log);
  ASSERT_TRUE(loaded);
  EXPECT_EQ(loaded->source, "some.relations");
  EXPECT_EQ(loaded->relations.size(), 2u);

  const proto::DatasetRef other =
      Keep(files, "other.relations", "90.0 91.0 1 0 0 0 0 0\n10.5 91.0 1 0 0 0 0 0\n");
  try {
    LoadJobRelations(files, other, log);
    ADD_FAILURE() << "relations of another log were accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("other.relations: none of its 2 relations"));
    EXPECT_THAT(e.what(), HasSubstr("run.clf"));
  }
  // A malformed line is named as the relations were uploaded.
  const proto::DatasetRef bad = Keep(files, "bad.relations", "10.0 11.0 1\n");
  try {
    LoadJobRelations(files, bad, log);
    ADD_FAILURE() << "a malformed relations file was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.relations:1"));
  }
}

}  // namespace
}  // namespace evoslam
