#include "worker/task_executor.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/engine/engine_proto.h"
#include "common/engine/island.h"
#include "common/io/carmen_reader.h"
#include "common/io/carmen_writer.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/methods/slam_methods.h"
#include "common/slam/rss/rss_proto.h"
#include "common/slam/rss/rss_slam.h"
#include "common/util/sha256.h"
#include "common/util/temp_dir.h"

namespace evoslam {
namespace {

// A short simulated log in a worker's dataset cache, and the SLAM task template for it.
class SlamTaskTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SimulationOptions sim;
    sim.laser.beams = 91;
    sim.noise.odometry.rotation_bias = 0.02;
    sim.max_scans = 80;
    WriteCarmen(Simulate(BuiltinWorld("office-cluster"), sim), dir_ / "drive.clf");
    std::ifstream in(dir_ / "drive.clf", std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    log_.set_sha256(Sha256Hex(bytes.str()));
    log_.set_size_bytes(bytes.str().size());
    log_.set_name("drive.clf");
    files_ = std::make_shared<DatasetFiles>(dir_ / "cache");
    files_->Put(log_, bytes.str());
    dataset_ = ReadCarmen(dir_ / "drive.clf");
    for (std::size_t i = 0; i < 60; ++i) poses_.push_back(dataset_.scans[i].odometry);
    slam_.mutable_rss()->mutable_global()->set_partitions(4);
  }

  // The periodic global search over scans [first, 60) of the odometry.
  GlobalSearchTask Task(std::size_t first) const {
    GlobalSearchTask task;
    task.index = 3;
    task.first = first;
    task.last = poses_.size();
    task.poses = poses_;
    task.max_error = RefineBounds(slam_.rss().global());
    return task;
  }

  proto::Task EvolveTask(const GlobalSearchTask& search, const Island& island,
                         std::size_t generations) const {
    proto::Task task;
    task.set_task_id("t-1");
    proto::ProblemSpec& problem = *task.mutable_problem();
    problem.set_kind(proto::JOB_KIND_SLAM);
    *problem.mutable_log() = log_;
    *problem.mutable_slam() = CompleteSlamParams(slam_);
    *problem.mutable_global_search() = ToProto(search);
    *task.mutable_evolve()->mutable_island() = ToProto(island.Checkpoint());
    task.mutable_evolve()->set_start(true);
    task.mutable_evolve()->set_generations(generations);
    return task;
  }

  static Island FreshIsland(const GlobalSearchParams& params) {
    StopCriteria stop;
    stop.max_generations = 10;
    return Island(GlobalIslandModel(params).algorithm, stop, Rng(7));
  }

  TempDir dir_{"evoslam-task-executor"};
  proto::DatasetRef log_;
  std::shared_ptr<DatasetFiles> files_;
  Dataset dataset_;
  std::vector<Pose2> poses_;
  proto::SlamParams slam_;
};

TEST_F(SlamTaskTest, AnIslandEvolvesOnTheWorkerAsItDoesOnTheCoordinatorsProblem) {
  const RssSlamParams params = CompleteSlamParams(slam_).rss();
  const GlobalSearchTask search = Task(20);
  const HitCountGrid base = BaseMapFor(dataset_, poses_, search.first, search.last, params);
  const GlobalSearchProblem problem =
      MakeGlobalSearchProblem(dataset_, search, params.global(), base);
  Island here = FreshIsland(params.global());
  const proto::Task task = EvolveTask(search, here, 4);
  here.Start(problem);
  here.Evolve(problem, 4);

  TaskExecutor executor(files_);
  EXPECT_TRUE(executor.Missing(task).empty()) << "a SLAM task needs its log alone";
  const proto::TaskResult first = executor.Run(task);
  ASSERT_TRUE(first.has_island()) << first.error().message();
  const Island there = Island::FromCheckpoint(FromProto(first.island().island()));
  EXPECT_EQ(there.algorithm().population().x, here.algorithm().population().x);
  EXPECT_EQ(there.algorithm().population().f, here.algorithm().population().f);
  // The same task again (as each epoch's tasks repeat the spec) is answered from memory, the
  // log gone from the cache, with the same island.
  std::filesystem::remove_all(files_->root());
  const proto::TaskResult again = executor.Run(task);
  ASSERT_TRUE(again.has_island()) << again.error().message();
  const Island same = Island::FromCheckpoint(FromProto(again.island().island()));
  EXPECT_EQ(same.algorithm().population().x, here.algorithm().population().x);
}

TEST_F(SlamTaskTest, ATaskThatDoesNotFitItsLogComesBackAsAnError) {
  // A task of the search over [20, 60) broken one way, and what its error must say.
  const std::vector<std::pair<std::function<void(proto::ProblemSpec&)>, std::string>> cases = {
      {[](proto::ProblemSpec& p) {
         proto::GlobalSearchSpec& spec = *p.mutable_global_search();
         for (int i = 0; i < 100; ++i) {
           spec.add_x(0.0);
           spec.add_y(0.0);
           spec.add_theta(0.0);
         }
         spec.set_last(spec.x_size());
       },
       "a global search up to scan 160 of a log of 80 scans"},
      {[](proto::ProblemSpec& p) { p.mutable_global_search()->set_first(60); }, "scans [60, 60)"},
      {[](proto::ProblemSpec& p) { p.clear_global_search(); }, "names no global search"},
      {[](proto::ProblemSpec& p) {
         p.mutable_slam()->mutable_rss()->mutable_global()->set_partitions(0);
       },
       "partition"},
  };
  TaskExecutor executor(files_);
  for (const auto& [change, says] : cases) {
    proto::Task task = EvolveTask(Task(20), FreshIsland(slam_.rss().global()), 1);
    change(*task.mutable_problem());
    const proto::TaskResult r = executor.Run(task);
    ASSERT_TRUE(r.has_error()) << says;
    EXPECT_NE(r.error().message().find(says), std::string::npos) << r.error().message();
  }
}

// Each global search's problem holds a base map as large as the job's map: a worker that kept
// the searches a job has finished would hold one such map per search.
TEST_F(SlamTaskTest, AWorkerHoldsOneGlobalSearchOfAJobAtATime) {
  TaskExecutor executor(files_);
  const Island island = FreshIsland(slam_.rss().global());
  const auto task = [&](const std::string& job, std::size_t first) {
    proto::Task t = EvolveTask(Task(first), island, 1);
    t.set_job_id(job);
    return t;
  };
  for (const std::size_t first : {20, 30, 40}) {
    const proto::TaskResult r = executor.Run(task("job-1", first));
    ASSERT_TRUE(r.has_island()) << r.error().message();
    EXPECT_EQ(executor.problems_held(), 1u) << "after the search from scan " << first;
  }
  ASSERT_TRUE(executor.Run(task("job-2", 20)).has_island());
  EXPECT_EQ(executor.problems_held(), 2u) << "another job's search is held beside it";
  // The last search's problem is let go before the next one is built, even one that fails.
  proto::Task broken = task("job-1", 50);
  broken.mutable_problem()->mutable_global_search()->set_first(60);
  ASSERT_TRUE(executor.Run(broken).has_error());
  EXPECT_EQ(executor.problems_held(), 1u);
}

}  // namespace
}  // namespace evoslam
