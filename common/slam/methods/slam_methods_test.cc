#include "common/slam/methods/slam_methods.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "common/slam/slam_params.h"
#include "common/util/error.h"
#include "common/util/error_testing.h"

namespace evoslam {
namespace {

using testing::ErrorOf;
using ::testing::HasSubstr;

TEST(SlamMethodsTest, EveryMethodTheParametersDeclareIsThere) {
  for (const std::string& name : SlamMethodNames()) EXPECT_EQ(FindSlamMethod(name).name(), name);
  EXPECT_THAT(ErrorOf([] { FindSlamMethod("gslam"); }), HasSubstr("(rss, immune)"));
}

TEST(SlamMethodsTest, CompletingSetsEveryParameterOfTheMethod) {
  const proto::SlamParams complete = CompleteSlamParams({});
  EXPECT_EQ(complete.method(), "rss");
  EXPECT_TRUE(complete.rss().local().has_particles());
  EXPECT_TRUE(complete.rss().global().has_preset());
  EXPECT_EQ(complete.SerializeAsString(), WithDefaults({}).SerializeAsString());
}

TEST(SlamMethodsTest, BadValuesAreRefusedByName) {
  const auto refused = [](const std::string& name, const std::string& value) {
    proto::SlamParams p;
    SetSlamParam(p, name, value);
    return ErrorOf([&] { CompleteSlamParams(p); });
  };
  EXPECT_THAT(refused("method", "gmapping"), HasSubstr("gmapping"));
  EXPECT_THAT(refused("method", "gmapping"), HasSubstr("(rss, immune)"));
  EXPECT_THAT(refused("local.fitness", "eval3"), HasSubstr("eval3"));
  EXPECT_THAT(refused("local.particles", "1"), HasSubstr("local.particles"));
  EXPECT_THAT(refused("local.iterations", "0"), HasSubstr("local.iterations"));
  EXPECT_THAT(refused("local.max_error_theta_rad", "-1"), HasSubstr("local.max_error"));
  EXPECT_THAT(refused("local.odometry_tie_pull", "1"), HasSubstr("local.odometry_tie_pull"));
  EXPECT_THAT(refused("local.refine.wall_share", "2"), HasSubstr("local.refine.wall_share"));
  EXPECT_THAT(refused("map.cell_size_m", "0"), HasSubstr("map.cell_size_m"));
  EXPECT_THAT(refused("global.partitions", "0"), HasSubstr("global.partitions"));
  EXPECT_THAT(refused("global.spread_y", "0"), HasSubstr("global.spread"));
  EXPECT_THAT(refused("global.beam_stride", "0"), HasSubstr("global.beam_stride"));
  EXPECT_THAT(refused("global.preset", "nope"), HasSubstr("nope"));
  EXPECT_THAT(refused("global.min_periodic_sharpening", "1"),
              HasSubstr("global.min_periodic_sharpening"));
  EXPECT_THAT(refused("loops.min_match_score", "0"), HasSubstr("loops.min_match_score"));
  EXPECT_THAT(refused("loops.min_side_agreement", "1.5"), HasSubstr("loops.min_side_agreement"));
  EXPECT_THAT(refused("loops.max_match_window_m", "1"), HasSubstr("loops.max_match_window_m"));
}

TEST(SlamMethodsTest, BadValuesOfTheImmuneMethodAreRefusedByName) {
  const auto refused = [](const std::string& name, const std::string& value) {
    proto::SlamParams p;
    SetSlamParam(p, "method", "immune");
    SetSlamParam(p, name, value);
    return ErrorOf([&] { CompleteSlamParams(p); });
  };
  EXPECT_THAT(refused("variant", "nsga2"), HasSubstr("nsga2"));
  EXPECT_THAT(refused("search.p_immunity", "1.5"), HasSubstr("p_immunity"));
  EXPECT_THAT(refused("search.population", "2"), HasSubstr("population"));
  EXPECT_THAT(refused("segments.encoding", "binary"), HasSubstr("encoding"));
  EXPECT_THAT(refused("segments.length_m", "0"), HasSubstr("length_m"));
  EXPECT_THAT(refused("evidence.max_belief", "1"), HasSubstr("max_belief"));
  EXPECT_THAT(refused("key_points.min_section_points", "0"), HasSubstr("min_section_points"));
  EXPECT_THAT(refused("scan_stride", "0"), HasSubstr("scan_stride"));
}

}  // namespace
}  // namespace evoslam
