#include "common/slam/slam_params.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/slam/loop_detector.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

std::string ErrorOf(const proto::SlamParams& p) {
  try {
    RssSlamParamsFromProto(p);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SlamParamsTest, UnsetFieldsTakeTheDefaults) {
  const RssSlamParams defaults;
  const RssSlamParams r = RssSlamParamsFromProto({});
  EXPECT_EQ(r.local.max_error, defaults.local.max_error);
  EXPECT_EQ(r.global.partitions, defaults.global.partitions);
  EXPECT_EQ(r.global_every, defaults.global_every);
  EXPECT_EQ(r.loops.min_score, defaults.loops.min_score);
  EXPECT_TRUE(r.global_search);
  const proto::SlamParams complete = CompleteSlamParams({});
  EXPECT_EQ(complete.method(), "rss");
  EXPECT_EQ(complete.seed(), 1u);
  EXPECT_EQ(complete.local_fitness(), "eval1");
  EXPECT_EQ(complete.generations(), 100u);
  EXPECT_EQ(complete.local_max_error_size(), 3);
}

TEST(SlamParamsTest, SetFieldsRoundTripAndZeroIsAValue) {
  proto::SlamParams p;
  p.set_global_every(0);  // only on loops
  p.set_w2(0.0);
  p.set_partitions(5);
  p.set_global_beam_stride(1);
  p.set_global_scored_scans(0);
  p.set_local_frontier_margin_m(0.15);
  p.set_local_odometry_pull(0.0);
  p.set_local_turn_error_per_rad(0.0);
  p.set_local_carried_turn_error(0.0);
  p.set_local_carried_turn_shift(0.0);
  p.set_local_hedged_shift_rad(0.0);
  p.set_local_refine_iterations(0);
  p.set_local_refine_max_shift_cells(1.5);
  p.set_local_refine_max_turn_rad(0.03);
  p.set_local_refine_wall_share(0.0);
  p.set_min_periodic_eq6_gain(0.0);
  p.set_min_eq7_gain(0.1);
  p.set_hold_loops(true);
  p.set_local_free_frontier(true);
  p.set_match_window_per_m(0.0);
  p.set_max_match_window_m(2.5);
  p.set_match_spread_score(0.0);
  p.set_match_spread_in_eq7(false);
  p.set_min_side_agreement(0.0);
  p.set_local_fitness("eval2");
  p.set_local_only(true);
  for (double v : {0.2, 0.3, 0.04}) p.add_local_max_error(v);
  p.set_seed(42);
  const RssSlamParams r = RssSlamParamsFromProto(p);
  EXPECT_EQ(r.global_every, 0u);
  EXPECT_EQ(r.global.w2, 0.0);
  EXPECT_EQ(r.global.partitions, 5u);
  EXPECT_EQ(r.global.beam_stride, 1u);
  EXPECT_EQ(r.global.scored_scans, 0u);
  EXPECT_EQ(r.local.frontier_margin, 0.15);
  EXPECT_EQ(r.local.odometry_pull, 0.0);
  EXPECT_EQ(r.local.turn_error_per_rad, 0.0);
  EXPECT_EQ(r.local.carried_turn_error, 0.0);
  EXPECT_EQ(r.local.carried_turn_shift, 0.0);
  EXPECT_EQ(r.local.hedged_shift, 0.0);
  EXPECT_EQ(r.local.refine.iterations, 0u);
  EXPECT_EQ(r.local.refine.max_shift_cells, 1.5);
  EXPECT_EQ(r.local.refine.wall_share, 0.0);
  EXPECT_EQ(r.min_periodic_eq6_gain, 0.0);
  EXPECT_EQ(r.local.refine.max_turn, 0.03);
  EXPECT_EQ(r.min_eq7_gain, 0.1);
  EXPECT_TRUE(r.hold_loops);
  EXPECT_TRUE(r.local.free_frontier);
  EXPECT_EQ(r.loops.match_window_per_metre, 0.0);
  EXPECT_EQ(r.loops.max_match_window, 2.5);
  EXPECT_EQ(r.loops.spread_score, 0.0);
  EXPECT_FALSE(r.loops.spread_weights_eq7);
  EXPECT_EQ(r.loops.min_side_agreement, 0.0);
  EXPECT_EQ(r.local.fitness, LocalFitness::kEval2);
  EXPECT_FALSE(r.global_search);
  EXPECT_EQ(r.local.max_error, Eigen::Vector3d(0.2, 0.3, 0.04));
  const proto::SlamParams complete = CompleteSlamParams(p);
  EXPECT_EQ(complete.seed(), 42u);
  // Completing is idempotent, and the complete form reads back to the same parameters.
  EXPECT_EQ(CompleteSlamParams(complete).SerializeAsString(), complete.SerializeAsString());
  EXPECT_EQ(RssSlamParamsFromProto(complete).local.max_error, r.local.max_error);
}

TEST(SlamParamsTest, BadFieldsAreNamed) {
  proto::SlamParams p;
  p.set_method("gmapping");
  EXPECT_NE(ErrorOf(p).find("gmapping"), std::string::npos);
  p = {};
  p.add_sigma(0.3);
  EXPECT_NE(ErrorOf(p).find("sigma"), std::string::npos);
  p = {};
  p.set_local_fitness("eval3");
  EXPECT_NE(ErrorOf(p).find("eval3"), std::string::npos);
  p = {};
  p.set_local_particles(1);
  EXPECT_NE(ErrorOf(p).find("particles"), std::string::npos);
  p.set_local_particles(100001);  // 4e9 was a bad_alloc
  EXPECT_NE(ErrorOf(p).find("particles"), std::string::npos);
  p = {};
  p.set_local_iterations(100001);
  EXPECT_NE(ErrorOf(p).find("iterations"), std::string::npos);
  p = {};
  p.set_partitions(100001);
  EXPECT_NE(ErrorOf(p).find("partitions"), std::string::npos);
  p = {};
  p.set_min_match_score(2.0);
  EXPECT_NE(ErrorOf(p).find("score"), std::string::npos);
  p = {};
  p.set_global_beam_stride(0);
  EXPECT_NE(ErrorOf(p).find("beam stride"), std::string::npos);
  p = {};
  p.set_local_frontier_margin_m(std::numeric_limits<double>::quiet_NaN());
  EXPECT_NE(ErrorOf(p).find("frontier margin"), std::string::npos);
  for (double pull : {-0.1, 1.0, std::numeric_limits<double>::quiet_NaN()}) {
    p = {};
    p.set_local_odometry_pull(pull);
    EXPECT_NE(ErrorOf(p).find("odometry pull"), std::string::npos) << pull;
  }
  p = {};
  p.set_local_turn_error_per_rad(-0.1);
  EXPECT_NE(ErrorOf(p).find("per radian turned"), std::string::npos);
  p = {};
  p.set_local_carried_turn_error(std::numeric_limits<double>::infinity());
  EXPECT_NE(ErrorOf(p).find("previous step's heading correction"), std::string::npos);
  p = {};
  p.set_local_carried_turn_shift(std::numeric_limits<double>::quiet_NaN());
  EXPECT_NE(ErrorOf(p).find("shift by the previous step's heading correction"), std::string::npos);
  for (double hedged : {-0.01, std::numeric_limits<double>::infinity()}) {
    p = {};
    p.set_local_hedged_shift_rad(hedged);
    EXPECT_NE(ErrorOf(p).find("hedged by a second swarm"), std::string::npos) << hedged;
  }
  p = {};
  p.set_min_side_agreement(-0.1);
  EXPECT_NE(ErrorOf(p).find("seen from the place's side"), std::string::npos);
  p = {};
  p.set_local_refine_max_shift_cells(-0.5);
  EXPECT_NE(ErrorOf(p).find("largest shift"), std::string::npos);
  p = {};
  p.set_local_refine_wall_share(2.0);
  EXPECT_NE(ErrorOf(p).find("wall share"), std::string::npos);
  p = {};
  p.set_min_eq7_gain(1.0);
  EXPECT_NE(ErrorOf(p).find("eq. 7 gain"), std::string::npos);
  p = {};
  p.set_min_periodic_eq6_gain(-0.1);
  EXPECT_NE(ErrorOf(p).find("eq. 6 gain"), std::string::npos);
  p = {};
  p.set_match_window_per_m(-0.01);
  EXPECT_NE(ErrorOf(p).find("growth per metre"), std::string::npos);
  p = {};
  p.set_max_match_window_m(1.0);  // below the 1.5 m window
  EXPECT_NE(ErrorOf(p).find("largest match window"), std::string::npos);
  p = {};
  p.set_match_spread_score(-1.0);
  EXPECT_NE(ErrorOf(p).find("spread's score scale"), std::string::npos);
  p = {};
  p.set_preset("nope");
  EXPECT_NE(ErrorOf(p).find("nope"), std::string::npos);
}

TEST(SlamParamsTest, GlobalSearchTasksRoundTrip) {
  const std::vector<Pose2> poses = {Pose2(0, 0, 0), Pose2(1, 0.5, 0.1), Pose2(2, 1, 0.2),
                                    Pose2(2.5, 1.5, 0.3)};
  GlobalSearchTask task;
  task.index = 7;
  task.first = 1;
  task.last = 4;
  task.poses = poses;
  task.loop = LoopConstraint{0, 3, Pose2(0.1, -0.2, 0.03)};
  Eigen::Matrix2d spread;  // loose along one diagonal of the world
  spread << 0.2, 0.15, 0.15, 0.2;
  task.loop->weight = LoopWeight(spread, 0.4);
  task.held = {LoopConstraint{0, 2, Pose2(-0.1, 0.2, 0.01)}};
  task.max_error = Eigen::Vector3d(0.3, 0.4, 0.05);
  std::vector<Pose2> storage;
  const GlobalSearchTask back = GlobalSearchTaskFromProto(ToProto(task), storage);
  EXPECT_EQ(back.index, 7u);
  EXPECT_EQ(back.first, 1u);
  EXPECT_EQ(back.last, 4u);
  ASSERT_EQ(back.poses.size(), 4u);
  EXPECT_EQ(back.poses[2].translation(), poses[2].translation());
  EXPECT_EQ(back.poses[3].theta(), poses[3].theta());
  ASSERT_TRUE(back.loop.has_value());
  EXPECT_EQ(back.loop->later, 3u);
  EXPECT_EQ(back.loop->relative.translation(), task.loop->relative.translation());
  EXPECT_EQ(back.loop->weight, task.loop->weight);
  ASSERT_EQ(back.held.size(), 1u);
  EXPECT_EQ(back.held[0].later, 2u);
  EXPECT_EQ(back.held[0].relative.translation(), task.held[0].relative.translation());
  EXPECT_EQ(back.max_error, task.max_error);
  task.loop.reset();
  EXPECT_FALSE(GlobalSearchTaskFromProto(ToProto(task), storage).loop.has_value());
}

TEST(SlamParamsTest, TasksThatDoNotHangTogetherAreRefused) {
  const std::vector<Pose2> poses = {Pose2(), Pose2(1, 0, 0), Pose2(2, 0, 0)};
  GlobalSearchTask task;
  task.first = 1;
  task.last = 3;
  task.poses = poses;
  std::vector<Pose2> storage;
  proto::GlobalSearchSpec spec = ToProto(task);
  spec.set_last(5);  // more scans than poses
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  spec = ToProto(task);
  spec.mutable_y()->RemoveLast();
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  spec = ToProto(task);
  spec.mutable_loop()->set_earlier(2);
  spec.mutable_loop()->set_later(1);
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  spec = ToProto(task);
  spec.set_first(3);
  EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  // A held loop must end in the stretch, which is what bends it, and within the log.
  for (const std::size_t later : {1u, 3u}) {
    spec = ToProto(task);
    spec.set_first(2);
    *spec.add_held() = ToProto(LoopClosure{LoopConstraint{0, later, Pose2()}, 0.0, 0.0});
    EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error) << later;
  }
  spec = ToProto(task);
  spec.set_first(2);
  *spec.add_held() = ToProto(LoopClosure{LoopConstraint{0, 2, Pose2()}, 0.0, 0.0});
  EXPECT_EQ(GlobalSearchTaskFromProto(spec, storage).held.size(), 1u);
  // A loop's weight must be a positive semi-definite matrix no larger than the identity: one
  // that is not would reward a miss, or count it more than 002 does.
  task.loop = LoopConstraint{0, 2, Pose2(2, 0, 0)};
  for (const std::vector<double>& weight :
       std::vector<std::vector<double>>{{1.0, 0.0},
                                        {1.0, 2.0, 1.0},
                                        {1.0, 1.0, 1.0},
                                        {0.5, std::nan(""), 0.5},
                                        {-0.1, 0.0, 1.0},
                                        {2.0, 0.0, 1.0},
                                        {1.0, 0.0, std::nan("")}}) {
    spec = ToProto(task);
    for (double v : weight) spec.mutable_loop()->add_weight(v);
    EXPECT_THROW(GlobalSearchTaskFromProto(spec, storage), Error);
  }
  spec = ToProto(task);
  for (double v : {1.0, 0.0, 0.5}) spec.mutable_loop()->add_weight(v);
  EXPECT_EQ(GlobalSearchTaskFromProto(spec, storage).loop->weight(1, 1), 0.5);
}

}  // namespace
}  // namespace evoslam
