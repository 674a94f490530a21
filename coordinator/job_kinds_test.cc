#include "coordinator/job_kinds.h"

#include <gtest/gtest.h>

#include <string>

#include "common/localization/localize_params.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

proto::DatasetRef Ref(char digit, const std::string& name) {
  proto::DatasetRef ref;
  ref.set_sha256(std::string(64, digit));
  ref.set_name(name);
  return ref;
}

proto::JobSpec SlamSpec() {
  proto::JobSpec spec;
  spec.set_kind(proto::JOB_KIND_SLAM);
  *spec.mutable_log() = Ref('a', "intel.clf");
  spec.mutable_slam()->mutable_rss()->mutable_global()->set_generations(20);
  return spec;
}

// What PrepareJobSpec refuses `spec` with; empty when it accepts it.
std::string Refusal(proto::JobSpec spec) {
  try {
    PrepareJobSpec(spec);
    return "";
  } catch (const Error& e) {
    return e.what();
  }
}

TEST(JobKindsTest, ASlamJobTakesTheSpecsSeedIslandsAndLogName) {
  proto::JobSpec spec = SlamSpec();
  spec.set_seed(42);
  spec.set_islands(3);
  PrepareJobSpec(spec);
  EXPECT_EQ(spec.slam().seed(), 42u);
  EXPECT_EQ(spec.slam().rss().global().islands(), 3u);
  EXPECT_EQ(spec.slam().log(), "intel.clf");
  EXPECT_EQ(spec.slam().rss().global().generations(), 20u);

  // Unset in the spec, the parameters' own stay.
  spec = SlamSpec();
  spec.mutable_slam()->set_seed(5);
  spec.mutable_slam()->set_log("logs/intel.gfs.log");
  PrepareJobSpec(spec);
  EXPECT_EQ(spec.slam().seed(), 5u);
  EXPECT_FALSE(spec.slam().rss().global().has_islands());
  EXPECT_EQ(spec.slam().log(), "logs/intel.gfs.log");
}

TEST(JobKindsTest, ALocalizationWithoutF2sToleranceGetsThePapersInItsSpec) {
  proto::JobSpec spec;
  spec.set_kind(proto::JOB_KIND_LOCALIZE);
  *spec.mutable_localize() = ToProto(LocalizeOptions{});
  spec.mutable_localize()->clear_f2_base_m();
  spec.mutable_localize()->clear_f2_slope();
  PrepareJobSpec(spec);
  EXPECT_EQ(spec.localize().f2_base_m(), FitnessParams{}.f2_base);
  EXPECT_EQ(spec.localize().f2_slope(), FitnessParams{}.f2_slope);

  // Given, they stay.
  spec.mutable_localize()->set_f2_base_m(0.06);
  PrepareJobSpec(spec);
  EXPECT_EQ(spec.localize().f2_base_m(), 0.06);
}

TEST(JobKindsTest, ABadSlamJobIsRefusedSayingWhatIsWrong) {
  proto::JobSpec spec = SlamSpec();
  spec.mutable_slam()->mutable_rss()->mutable_global()->set_spread_x(0.0);
  EXPECT_NE(Refusal(spec).find("global.spread"), std::string::npos) << Refusal(spec);
  spec = SlamSpec();
  spec.mutable_slam()->set_method("gmapping");
  EXPECT_NE(Refusal(spec).find("gmapping"), std::string::npos) << Refusal(spec);
  spec = SlamSpec();
  spec.clear_slam();
  EXPECT_NE(Refusal(spec).find("a SLAM job needs its parameters"), std::string::npos);
  spec = SlamSpec();
  *spec.mutable_map() = Ref('b', "map.yaml");
  EXPECT_NE(Refusal(spec).find("builds its own map"), std::string::npos);
  spec = SlamSpec();
  spec.set_max_evaluations(1000);
  EXPECT_NE(Refusal(spec).find("max_evaluations"), std::string::npos);
  spec = SlamSpec();
  spec.set_kind(proto::JOB_KIND_UNSPECIFIED);
  EXPECT_NE(Refusal(spec).find("job kind 0 is not one this coordinator runs"), std::string::npos);
}

TEST(JobKindsTest, ASlamJobReadsItsLogAndRelationsButNoMap) {
  proto::JobSpec spec = SlamSpec();
  auto refs = JobDatasets(spec);
  ASSERT_EQ(refs.size(), 1u);
  EXPECT_EQ(std::string(refs[0].first), "log");
  EXPECT_EQ(refs[0].second.name(), "intel.clf");
  *spec.mutable_relations() = Ref('c', "intel.relations");
  refs = JobDatasets(spec);
  ASSERT_EQ(refs.size(), 2u);
  EXPECT_EQ(std::string(refs[1].first), "relations");

  // A localization reads its map, named even when missing so that the submit says so.
  spec.set_kind(proto::JOB_KIND_LOCALIZE);
  refs = JobDatasets(spec);
  ASSERT_EQ(refs.size(), 3u);
  EXPECT_EQ(std::string(refs[1].first), "map");
}

}  // namespace
}  // namespace evoslam
