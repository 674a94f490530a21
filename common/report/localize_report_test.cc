#include "common/report/localize_report.h"

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "common/util/error.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

proto::LocalizeReport SampleReport() {
  proto::LocalizeReport r;
  auto& p = *r.mutable_params();
  p.set_map("world.lines");
  p.set_log("log.clf");
  p.set_fitness("f3");
  p.set_estimator("2d");
  p.set_optimizer("de");
  p.set_strategy("rand1exp");
  p.set_population(25);
  p.set_generations(25);
  p.set_window_m(0.6);
  p.set_heading_window_deg(30);
  r.set_scans(220);
  r.set_evaluations(143000);
  r.set_runtime_s(0.5);
  r.set_scans_per_second(440);
  r.set_threads(2);
  return r;
}

TEST(LocalizeReportTest, SummarySaysWhatRanAndHowFast) {
  const std::string s = FormatSummary(SampleReport());
  EXPECT_NE(s.find("localized 220 scans of log.clf in world.lines"), std::string::npos) << s;
  EXPECT_NE(s.find("de rand1exp (population 25, generations 25)"), std::string::npos) << s;
  EXPECT_NE(s.find("runtime 0.50 s (440.00 scans/s, 2 threads), 143000"), std::string::npos) << s;
  EXPECT_EQ(s.find("RMS"), std::string::npos) << "no ground truth, no RMS line";
  EXPECT_EQ(s.find("relative"), std::string::npos);
}

TEST(LocalizeReportTest, SummaryShowsErrorsInCentimetresAndDegrees) {
  proto::LocalizeReport r = SampleReport();
  AbsoluteErrors a;
  a.poses = 220;
  a.rms_x = 0.0071;
  a.rms_y = 0.0066;
  a.rms_theta = 0.2 * std::numbers::pi / 180;
  a.max_translation = 0.0245;
  a.aligned_rms_translation = 0.0052;
  a.scale_aligned_rms_translation = 0.0031;
  a.alignment_scale = 0.99214;
  *r.mutable_absolute_errors() = ToProto(a);
  EXPECT_NEAR(r.absolute_errors().rms_theta_deg(), 0.2, 1e-12);
  RelationErrors e;
  e.relations = 219;
  e.translation_mean = 0.0114;
  e.translation_std = 0.0073;
  e.rotation_mean = 0.5 * std::numbers::pi / 180;
  e.rotation_sq_mean = e.rotation_mean * e.rotation_mean;
  *r.mutable_relation_errors() = ToProto(e, "truth");
  EXPECT_NEAR(r.relation_errors().rotation_sq_mean_deg2(), 0.25, 1e-12);
  const std::string s = FormatSummary(r);
  EXPECT_NE(s.find("x 0.71 cm, y 0.66 cm, heading 0.20 deg (max 2.45 cm); aligned: 0.52 cm; "
                   "aligned and scaled (x0.9921): 0.31 cm"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("relative error (truth, 219 relations): 0.0114 +- 0.0073 m, 0.500"),
            std::string::npos)
      << s;
  e.relations = 1;
  *r.mutable_relation_errors() = ToProto(e, "truth");
  EXPECT_NE(FormatSummary(r).find("relative error (truth, 1 relation): "), std::string::npos)
      << FormatSummary(r);
  e = {};
  e.skipped = 12;
  *r.mutable_relation_errors() = ToProto(e, "truth");
  EXPECT_NE(FormatSummary(r).find(
                "relative error (truth, 0 relations): none of the 12 relations joins two scans"),
            std::string::npos)
      << FormatSummary(r);
}

TEST(LocalizeReportTest, SummaryGivesF2sTolerance) {
  proto::LocalizeReport r = SampleReport();
  r.mutable_params()->set_f2_base_m(0.06);
  r.mutable_params()->set_f2_slope(59.0 / 6000.0);
  EXPECT_EQ(FormatSummary(r).find("within"), std::string::npos) << "F3 has no tolerance";
  r.mutable_params()->set_fitness("f2");
  const std::string s = FormatSummary(r);
  EXPECT_NE(s.find("  f2 (within 0.060 m + 0.0098 x the two ranges), 2d estimator, de rand1exp "
                   "(population 25, generations 25), window 0.60 m"),
            std::string::npos)
      << s;
}

TEST(LocalizeReportTest, SummaryGivesF3sCapWhenThereIsOne) {
  proto::LocalizeReport r = SampleReport();
  EXPECT_EQ(FormatSummary(r).find("capped"), std::string::npos) << "the papers' F3 has no cap";
  r.mutable_params()->set_f3_cap_m(0.3);
  const std::string s = FormatSummary(r);
  EXPECT_NE(s.find("  f3 (each beam's difference capped at 0.300 m), 2d estimator"),
            std::string::npos)
      << s;
}

TEST(LocalizeReportTest, SummaryNamesTheOdometryStallsFilledIn) {
  proto::LocalizeReport r = SampleReport();
  EXPECT_EQ(FormatSummary(r).find("stalled"), std::string::npos) << "none, no line";
  *r.add_odometry_stalls() = ToProto(OdometryStall{3, 6, Pose2(0.3, -0.4, -0.25)});
  EXPECT_EQ(r.odometry_stalls(0).first(), 3u);
  EXPECT_EQ(r.odometry_stalls(0).last(), 6u);
  EXPECT_DOUBLE_EQ(r.odometry_stalls(0).catch_up_m(), 0.5);
  EXPECT_DOUBLE_EQ(r.odometry_stalls(0).catch_up_rad(), -0.25);
  const std::string s = FormatSummary(r);
  EXPECT_NE(s.find("  odometry stalled while the robot moved, filled in by time: scans 3 to 6 "
                   "(then 0.50 m and -14.3 deg)\n"),
            std::string::npos)
      << s;
}

TEST(LocalizeReportTest, JsonRoundTripsWithZeroFieldsSpelledOut) {
  const TempDir dir;
  const auto path = dir / "report.json";
  proto::LocalizeReport r = SampleReport();
  r.mutable_params()->set_seed(0);
  WriteJson(r, path);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("\"seed\": \"0\""), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\"heading_window_deg\": 30"), std::string::npos) << text.str();
  proto::LocalizeReport back;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(text.str(), &back).ok());
  EXPECT_EQ(back.SerializeAsString(), r.SerializeAsString());
}

TEST(LocalizeReportTest, UnwritablePathIsAnErrorNamingIt) {
  try {
    WriteJson(SampleReport(), "/nonexistent-dir/report.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/report.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace evoslam
