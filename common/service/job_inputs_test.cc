#include "common/service/job_inputs.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <string>

#include "common/localization/localize_params.h"
#include "common/sensor/dataset.h"
#include "common/service/dataset_files.h"
#include "common/service/localize_inputs.h"
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

// A log of two scans, for jobs whose map is what a test is about.
constexpr const char* kTwoScanLog =
    "FLASER 3 1 1 1 0 0 0 0 0 0 1.0 host 1.0\nFLASER 3 1 1 1 0 0 0 0 0 0 2.0 host 2.0\n";

// A map_server YAML file for the image `image`, 10 cm cells.
std::string MapYaml(const std::string& image) {
  return "image: " + image +
         "\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
         "free_thresh: 0.196\n";
}

// The InputError that loading the inputs of a localize job with this map throws.
InputError LocalizeInputsError(DatasetFiles& files, const proto::DatasetRef& map,
                               const proto::DatasetRef& image = {}) {
  const proto::DatasetRef log = Keep(files, "walk.clf", kTwoScanLog);
  try {
    LoadLocalizeInputs(files, log, map, image, ToProto(LocalizeOptions{}));
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "the map was accepted";
  return InputError("", 0, "");
}

TEST(LoadLocalizeInputsTest, AFaultInAMapsImageNamesTheImageAsUploaded) {
  TempDir dir;
  DatasetFiles files(dir / "cache");
  const proto::DatasetRef yaml = Keep(files, "site/map.yaml", MapYaml("map.pgm"));
  // Line 5 holds a value above maxval.
  const proto::DatasetRef pgm = Keep(files, "site/map.pgm", "P2\n2 2\n255\n0 0\n0 300\n");
  const InputError e = LocalizeInputsError(files, yaml, pgm);
  EXPECT_EQ(e.source(), "site/map.pgm");
  EXPECT_EQ(e.line(), 5u);
}

TEST(LoadLocalizeInputsTest, AMapWithoutWallsIsRefused) {
  TempDir dir;
  DatasetFiles files(dir / "cache");
  const InputError lines = LocalizeInputsError(files, Keep(files, "empty.lines", "# no walls\n"));
  EXPECT_EQ(lines.source(), "empty.lines");
  EXPECT_THAT(lines.message(), HasSubstr("no walls"));

  const proto::DatasetRef yaml = Keep(files, "free.yaml", MapYaml("free.pgm"));
  const proto::DatasetRef pgm = Keep(files, "free.pgm", "P2\n2 1\n255\n255 255\n");
  const InputError grid = LocalizeInputsError(files, yaml, pgm);
  EXPECT_EQ(grid.source(), "free.yaml");
  EXPECT_THAT(grid.message(), HasSubstr("no occupied cell"));
}

// Every way a map's YAML could name a file that is not its own image.
const char* const kForeignImages[] = {"/etc/secret.pgm",
                                      "../secret.pgm",
                                      "sub/../../secret.pgm",
                                      "./secret.pgm",
                                      "%2e%2e%2fsecret.pgm",
                                      "~/secret.pgm",
                                      "/proc/self/root/etc/secret.pgm",
                                      "\"../secret.pgm\"",
                                      "own.pgm/../x.pgm",
                                      "file:///etc/secret.pgm"};

TEST(CheckMapImageIsOwnTest, AMapNamesOnlyTheImageUploadedWithIt) {
  proto::DatasetRef map, image;
  map.set_name("site/map.yaml");
  image.set_name("site/own.pgm");
  image.set_sha256(std::string(64, 'a'));
  EXPECT_NO_THROW(CheckMapImageIsOwn(MapYaml("own.pgm"), map, image));
  EXPECT_NO_THROW(CheckMapImageIsOwn(MapYaml("'own.pgm'"), map, image));
  for (const char* foreign : kForeignImages) {
    try {
      CheckMapImageIsOwn(MapYaml(foreign), map, image);
      ADD_FAILURE() << foreign << " was accepted";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("must be the one uploaded with the job")) << foreign;
    }
  }
  // Without its image a map YAML names nothing it may read.
  EXPECT_THROW(CheckMapImageIsOwn(MapYaml("own.pgm"), map, {}), Error);
  EXPECT_TRUE(IsMapYaml(map));
  EXPECT_FALSE(IsMapYaml(image));
}

TEST(LoadLocalizeInputsTest, AMapNamingAFileOutsideTheJobIsNeverRead) {
  TempDir dir;
  DatasetFiles files(dir / "cache");
  // A private image on this host, readable by the process: it must not become the job's map.
  const std::string secret = (dir / "secret.pgm").string();
  {
    std::ofstream out(secret);
    out << "P2\n2 1\n255\n0 0\n";
  }
  const proto::DatasetRef pgm = Keep(files, "own.pgm", "P2\n2 1\n255\n0 255\n");
  const proto::DatasetRef log = Keep(files, "walk.clf", kTwoScanLog);
  for (const std::string& image :
       {secret, std::string("../../secret.pgm"), std::string("../") + pgm.sha256() + "/own.pgm"}) {
    const proto::DatasetRef yaml = Keep(files, "map.yaml", MapYaml(image));
    try {
      LoadLocalizeInputs(files, log, yaml, pgm, ToProto(LocalizeOptions{}));
      ADD_FAILURE() << image << " was read";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("must be the one uploaded with the job")) << image;
    }
    // Nor without an image of its own.
    EXPECT_THROW(LoadLocalizeInputs(files, log, yaml, {}, ToProto(LocalizeOptions{})), Error);
  }
}

TEST(LoadSharedJobLogTest, ALogIsParsedOnceWhileItIsHeld) {
  TempDir dir;
  // A coordinator's cache and a worker's, holding the same bytes.
  DatasetFiles coordinator(dir / "coordinator"), worker(dir / "worker");
  const std::string clf =
      "FLASER 3 1.0 2.0 3.0 0 0 0 0 0 0 1.5 nohost 1.5\n"
      "FLASER 3 1.0 2.0 3.0 0.1 0 0 0.1 0 0 1.6 nohost 1.6\n";
  const proto::DatasetRef ref = Keep(coordinator, "run.clf", clf);
  Keep(worker, "run.clf", clf);
  std::shared_ptr<const Dataset> first = LoadSharedJobLog(coordinator, ref, false);
  std::shared_ptr<const Dataset> second = LoadSharedJobLog(worker, ref, false);
  EXPECT_EQ(first.get(), second.get());
  EXPECT_EQ(first->source, "run.clf");
  EXPECT_EQ(first->scans.size(), 2u);
  EXPECT_NE(LoadSharedJobLog(worker, ref, true).get(), first.get()) << "a lenient load differs";
  proto::DatasetRef renamed = ref;
  renamed.set_name("other.clf");
  Keep(worker, "other.clf", clf);
  EXPECT_EQ(LoadSharedJobLog(worker, renamed, false)->source, "other.clf");
  // Nothing keeps a log that nobody holds.
  const std::weak_ptr<const Dataset> held = first;
  first.reset();
  EXPECT_FALSE(held.expired());
  second.reset();
  EXPECT_TRUE(held.expired());
}

}  // namespace
}  // namespace evoslam
