#ifndef EVOSLAM_COMMON_SLAM_SLAM_METHOD_H_
#define EVOSLAM_COMMON_SLAM_SLAM_METHOD_H_

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/engine/archipelago.h"
#include "common/grid/occupancy_grid.h"
#include "common/io/trajectory_io.h"
#include "common/optim/problem.h"
#include "common/sensor/dataset.h"
#include "common/sensor/odometry_stalls.h"
#include "common/slam/loop_detector.h"
#include "common/slam/memory_need.h"
#include "evoslam/service.pb.h"
#include "evoslam/slam.pb.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// Where a run stands: `done` of the `total` scans it maps, the fitness evaluations so far, and
// the step under way inside the run while it stands there, if any (for rss a global search,
// `step_done` of `step_total` generations).
struct SlamProgress {
  std::size_t done = 0;
  std::size_t total = 0;
  std::uint64_t evaluations = 0;
  std::string step;  // empty: none
  std::size_t step_done = 0;
  std::size_t step_total = 0;
};

// What the run of a SLAM method needs from where it runs: the embedded service, a coordinator,
// or a test. Every hook may be left empty.
struct SlamHooks {
  // Where the run stands; called once at the start, a resumed run's included, then as it
  // advances. `done` never goes back, within a run nor across a resume.
  std::function<void(const SlamProgress& progress)> progress;
  // Offered after every step: the method's state, serialised only when the caller asks for it
  // by calling `serialize`. A run resumed from those bytes ends as the uninterrupted run does.
  std::function<void(const std::function<std::string()>& serialize)> checkpoint;
  // The bytes of the last checkpoint to resume from; empty: start afresh.
  std::string resume;
  // The stepper of an island search whose problem `task` describes (its method's task message
  // set; the caller adds the log and the parameters), for workers to run; empty: local threads.
  std::function<IslandStepper(const proto::ProblemSpec& task)> islands;
};

// The Pareto front a multi-objective search ended with (all objectives minimised), for the outputs.
struct ParetoFront {
  std::string label;                    // which search, e.g. "window 2: scans 120-241"
  std::vector<std::string> objectives;  // the objectives' names, one per row of f
  Eigen::MatrixXd f;                    // objectives x members
  std::vector<double> start;            // the objectives where the search started; empty: unknown
  std::size_t chosen = 0;               // the member the result applies
};

// What every SLAM method returns.
struct SlamResult {
  std::vector<StampedPose> trajectory;  // one pose per scan mapped, the laser's
  OccupancyGrid map;                    // the map the outputs write and draw
  std::vector<LoopClosure> loops;       // places seen twice, drawn on the picture
  // Where the log's odometry stalled while the robot moved (FindOdometryStalls).
  std::vector<OdometryStall> odometry_stalls;
  double seconds = 0.0;           // the whole run's, across resumes
  std::uint64_t evaluations = 0;  // fitness evaluations of every search
  // The method's own report fields (its message in SlamReport), filled by the method.
  proto::SlamReport method_report;
  // The fronts of a method whose searches have several objectives, in the order it ran them.
  std::vector<ParetoFront> pareto_fronts = {};
};

// A command-line flag of a method's: it sets the parameter `param` (a dotted path from the top)
// to its value, or, for a switch, to `value`.
struct SlamFlag {
  std::string flag, param, help;
  std::string value;  // a switch's; empty: the flag takes a value
  // An older name of a flag that takes a value, still accepted with a deprecation warning.
  std::string deprecated = {};
};

// A SLAM method: paper 002's reduced-search-space SLAM, and the methods to come, each a peer
// behind this interface. A method is stateless: every call takes the run's parameters.
class SlamMethod {
 public:
  virtual ~SlamMethod() = default;

  // The method's name, as --method and SlamParams.method give it, and the name of its message
  // field in SlamParams.
  virtual std::string_view name() const = 0;
  // Throws Error naming the first parameter of the method's message that is out of its range.
  virtual void Validate(const proto::SlamParams& params) const = 0;
  // How many islands its searches evolve at once (1 for a method without island searches): the
  // embedded service starts as many workers.
  virtual std::size_t Islands(const proto::SlamParams& params) const = 0;
  // Sets that number, as a job's spec may.
  virtual void SetIslands(proto::SlamParams& params, std::uint32_t islands) const = 0;
  // The memory Run would take over `dataset`, estimated from its extent without running (to
  // within a fifth or so): for refusing a run that cannot fit before it starts.
  virtual MemoryNeed PeakMemory(const Dataset& dataset, const proto::SlamParams& params) const = 0;
  // Maps the first ScansToMap scans of `dataset`. The result is a function of the log and the
  // parameters (the seed included) alone, wherever its searches run.
  virtual SlamResult Run(const Dataset& dataset, const proto::SlamParams& params,
                         const SlamHooks& hooks) const = 0;
  // The problem of an island search task that Run handed to SlamHooks::islands, rebuilt from the
  // task and the log on a worker. Throws Error for a task that does not fit the log.
  virtual std::shared_ptr<const Problem> TaskProblem(const Dataset& dataset,
                                                     const proto::ProblemSpec& task) const = 0;
  // The flags of the parameters users tune most; --param and --config reach every one.
  virtual std::vector<SlamFlag> Flags() const = 0;
  // The summary's lines for the method's own report fields, each starting with two spaces.
  virtual std::string Summary(const proto::SlamReport& report) const = 0;
};

// The number of scans a run over `dataset` maps (SlamParams.max_scans).
std::size_t ScansToMap(const Dataset& dataset, const proto::SlamParams& params);

// The occupancy grid of the log's first trajectory.size() scans at those poses, free where the
// beams pass and occupied where they end, in cells of `cell_size` m or as much coarser as it takes
// to fit in OccupancyGrid::kMaxCells (with a warning): a run must not be lost for want of a fine
// picture of it.
OccupancyGrid OccupancyGridAtPoses(const Dataset& dataset, std::span<const StampedPose> trajectory,
                                   double cell_size);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_SLAM_METHOD_H_
