// Paper 002's SLAM as a job of the service.

#include "common/io/carmen_reader.h"
#include "common/io/carmen_writer.h"
#include "common/io/relations.h"
#include "common/report/slam_outputs.h"
#include "common/sim/simulator.h"
#include "common/sim/world.h"
#include "common/slam/methods/slam_methods.h"
#include "tests/service_fixture.h"

namespace evoslam::service_test {
namespace {

// Paper 002's SLAM as a job: a drive through the simulated office cluster whose odometry drifts,
// long enough for periodic global searches and a loop (under the sanitizers, periodic searches
// alone), with searches small enough that the job takes seconds.
class SlamJobTest : public ServiceTest {
 protected:
  static constexpr std::uint64_t kSeed = 3;
  static constexpr std::size_t kScans = Scans(200);

  void SetUp() override {
    evoslam::SimulationOptions sim;
    sim.laser.beams = 61;
    sim.noise.odometry.rotation_bias = 0.02;
    sim.max_scans = kScans;
    evoslam::WriteCarmen(evoslam::Simulate(evoslam::BuiltinWorld("office-cluster"), sim),
                         DriveLog());
    // The true motion between scans ten apart, stamped as the log reads back.
    std::ofstream relations(DriveRelations());
    relations.precision(17);
    const evoslam::Dataset drive = evoslam::ReadCarmen(DriveLog());
    for (std::size_t i = 0; i + 10 < drive.scans.size(); i += 10) {
      const evoslam::LaserScan &a = drive.scans[i], &b = drive.scans[i + 10];
      const evoslam::Pose2 delta = a.true_pose->inverse() * *b.true_pose;
      relations << a.timestamp << ' ' << b.timestamp << ' ' << delta.x() << ' ' << delta.y()
                << " 0 0 0 " << delta.theta() << '\n';
    }
  }

  fs::path DriveLog() const { return dir_ / "drive.clf"; }
  fs::path DriveRelations() const { return dir_ / "drive.relations"; }

  static proto::SlamParams Params() {
    proto::SlamParams p;
    p.set_log("drive.clf");
    p.set_seed(kSeed);
    p.mutable_rss()->mutable_global()->set_islands(2);
    p.mutable_rss()->mutable_global()->set_generations(
        20);  // two epochs: migrants travel between them
    p.mutable_rss()->mutable_global()->set_partitions(4);
    p.mutable_rss()->mutable_global()->set_every_scans(static_cast<std::uint32_t>(Scans(100)));
    p.mutable_rss()->mutable_loops()->set_check_interval_scans(
        1);  // the drive's one revisit lasts a few scans
    // Ten times 002's PSO iterations: the local search then lasts about a second, a window wide
    // enough for a test to catch the job part-way between its polls.
    p.mutable_rss()->mutable_local()->set_iterations(300);
    // A local search of one fixed cube per step, unrefined, leaves the revisit off the map, and its
    // match, not distinct enough to be trusted in a real run, is let through: here it only has to
    // start a loop's search, whose tasks the service must run as the method does in process.
    p.mutable_rss()->mutable_local()->set_recentres(0);
    p.mutable_rss()->mutable_local()->set_heading_range_per_turn(0.0);
    p.mutable_rss()->mutable_local()->set_heading_range_per_correction(0.0);
    p.mutable_rss()->mutable_local()->mutable_refine()->set_iterations(0);
    p.mutable_rss()->mutable_loops()->set_min_distinctness(0.0);
    return p;
  }

  // The job's files as its method makes them in this process, its island searches on local
  // threads: what the service must hand back.
  fs::path SlamReference() {
    const fs::path out = dir_ / "slam-reference";
    const evoslam::Dataset drive = evoslam::ReadCarmen(DriveLog());
    const evoslam::SlamResult result =
        evoslam::FindSlamMethod(Params().method()).Run(drive, Params(), {});
    EXPECT_GT(result.method_report.rss().global_searches_size(), 0)
        << "no global search: the job sends no task";
    if (kScaleDown == 1) {
      EXPECT_FALSE(result.loops.empty()) << "no loop: none is searched";
    }
    // Named as the service names them: by the path they were uploaded from.
    const evoslam::NamedRelations relations{DriveRelations().string(),
                                            evoslam::ReadRelations(DriveRelations())};
    fs::create_directories(out);
    for (const proto::ResultFile& f :
         evoslam::SlamOutputs(drive, evoslam::CompleteSlamParams(Params()), result, relations, 1)) {
      std::ofstream(out / f.name(), std::ios::binary) << f.content();
    }
    return out;
  }

  // Submits the job as a client does: datasets uploaded, seed and islands in the spec. An empty
  // `relations` is the drive's.
  std::string SubmitSlam(evoslam::ServiceClient& client, const proto::SlamParams& params = Params(),
                         const fs::path& relations = {}) {
    proto::JobSpec spec;
    spec.set_kind(proto::JOB_KIND_SLAM);
    *spec.mutable_log() = client.Upload(DriveLog());
    *spec.mutable_relations() = client.Upload(relations.empty() ? DriveRelations() : relations);
    *spec.mutable_slam() = params;
    spec.mutable_slam()->clear_seed();
    spec.mutable_slam()->mutable_rss()->mutable_global()->clear_islands();
    spec.set_seed(kSeed);
    spec.set_islands(2);
    return client.Submit(spec);
  }

  static void ExpectSameSlamOutputs(const fs::path& expected, const fs::path& actual) {
    ExpectSameTrajectory(expected, actual);
    EXPECT_TRUE(ReadAll(expected / "map.pgm") == ReadAll(actual / "map.pgm")) << "map.pgm differs";
    EXPECT_EQ(StableReport(expected / "report.json"), StableReport(actual / "report.json"));
    EXPECT_NE(ReadAll(actual / "report.json").find("\"relation_errors\""), std::string::npos)
        << "the relations were not scored";
  }
};

TEST_F(SlamJobTest, OnTwoWorkerProcessesItWritesWhatTheMethodWritesInProcess) {
  const fs::path reference = SlamReference();
  const CoordinatorProcess c = StartCoordinator("coordinator");
  const std::vector<ChildProcess*> workers = {&StartWorker("worker1", c.workers),
                                              &StartWorker("worker2", c.workers)};
  auto client = Client(c.clients);
  WaitForWorkers(client, 2);

  // A bad parameter is refused at submit, by name.
  proto::SlamParams bad = Params();
  bad.mutable_rss()->mutable_global()->set_spread_x(0.0);
  try {
    SubmitSlam(client, bad);
    ADD_FAILURE() << "a SLAM job with a Gaussian of no width was accepted";
  } catch (const evoslam::ProtocolError& e) {
    EXPECT_EQ(e.code(), proto::ERROR_CODE_INVALID);
    EXPECT_NE(std::string(e.what()).find("global.spread"), std::string::npos) << e.what();
  }
  // A malformed relations file fails the job, by name and line, before a scan is searched.
  std::ofstream(Path("bad.relations")) << "1.0 2.0 0.5\n";
  const proto::JobStatus failed =
      WaitForEnd(client, SubmitSlam(client, Params(), Path("bad.relations")));
  EXPECT_EQ(failed.state(), proto::JOB_STATE_FAILED) << Describe(failed);
  EXPECT_NE(failed.error().find("bad.relations:1"), std::string::npos) << Describe(failed);
  EXPECT_EQ(failed.done(), 0u) << Describe(failed);

  const std::string job_id = SubmitSlam(client);
  const proto::JobStatus end = WaitForEnd(client, job_id);
  ASSERT_EQ(end.state(), proto::JOB_STATE_SUCCEEDED) << Describe(end);
  FetchResult(client, job_id, Path("remote"));
  ExpectSameSlamOutputs(reference, Path("remote"));
  // The global searches' islands ran on both processes: each fetched the log. Their logs tell
  // even when a loaded machine made the coordinator drop and readmit a worker, which starts its
  // task count afresh.
  for (ChildProcess* w : workers) {
    EXPECT_NE(w->Log().find("fetching dataset " + DriveLog().string()), std::string::npos)
        << w->log_path();
  }
}

TEST_F(SlamJobTest, ItResumesFromItsCheckpointAfterTheCoordinatorIsKilledAndRestarted) {
  const fs::path reference = SlamReference();
  const CoordinatorProcess c = StartCoordinator("coordinator");
  StartWorker("worker1", c.workers);
  StartWorker("worker2", c.workers);
  std::string job_id;
  proto::JobStatus before;
  {
    auto client = Client(c.clients);
    WaitForWorkers(client, 2);
    job_id = SubmitSlam(client);
    before = WaitForProgress(client, job_id, kScans / 3, "slam");
  }
  const CoordinatorProcess restarted = KillAndResume(c, job_id, before);
  ASSERT_FALSE(HasFailure());
  auto client = Client(restarted.clients);
  FetchResult(client, job_id, Path("result"));
  ExpectSameSlamOutputs(reference, Path("result"));
}

}  // namespace
}  // namespace evoslam::service_test
