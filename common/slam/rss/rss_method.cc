#include "common/slam/rss/rss_method.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "common/io/text_fields.h"
#include "common/slam/rss/local_search.h"
#include "common/slam/rss/rss_proto.h"
#include "common/slam/rss/rss_slam.h"
#include "common/slam/slam_params.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// The rss parameters of a task from the wire, each set, checked before anything is built on them.
RssSlamParams ValidRssParams(const proto::SlamParams& params) {
  RssSlamParams rss = WithDefaults(params).rss();
  ValidateRssSlamParams(rss);
  return rss;
}

// A global search as the coordinator built it, with the poses and the base map it refers to.
// Its members refer to one another: it is built in place and never moved.
struct GlobalSearchOnBase {
  GlobalSearchOnBase(const Dataset& dataset, const proto::ProblemSpec& spec)
      : params(ValidRssParams(spec.slam())),
        task(GlobalSearchTaskFromProto(spec.global_search(), poses)),
        base(BaseMapFor(dataset, poses, task.first, task.last, params)),
        problem(MakeGlobalSearchProblem(dataset, task, params.global(), base)) {}
  GlobalSearchOnBase(const GlobalSearchOnBase&) = delete;
  GlobalSearchOnBase& operator=(const GlobalSearchOnBase&) = delete;

  RssSlamParams params;
  std::vector<Pose2> poses;  // filled by task's initialiser, which comes after
  GlobalSearchTask task;
  HitCountGrid base;
  GlobalSearchProblem problem;
};

proto::RssRunReport RunReport(const RssSlamResult& result) {
  proto::RssRunReport report;
  report.set_local_evaluations(result.local_evaluations);
  report.set_global_evaluations(result.global_evaluations);
  *report.mutable_times() = ToProto(result.times);
  for (const GlobalSearchRecord& g : result.global_searches) {
    *report.add_global_searches() = ToProto(g);
  }
  return report;
}

}  // namespace

void RssMethod::Validate(const proto::SlamParams& params) const {
  ValidateRssSlamParams(params.rss());
}

std::size_t RssMethod::Islands(const proto::SlamParams& params) const {
  const proto::RssGlobalSearch& global = params.rss().global();
  return global.enabled() ? global.islands() : 1;
}

void RssMethod::SetIslands(proto::SlamParams& params, std::uint32_t islands) const {
  params.mutable_rss()->mutable_global()->set_islands(islands);
}

MemoryNeed RssMethod::PeakMemory(const Dataset& dataset, const proto::SlamParams& params) const {
  const proto::SlamParams complete = WithDefaults(params);
  const proto::RssMap& map = complete.rss().map();
  const SearchMapExtent extent = SearchMapExtentFor(dataset, map);
  // Per cell of the search map, measured on simulated drives at 5 mm to 2 cm cells and on the
  // real logs, with room to spare: the tiles of counts and ray crossings where the scans reach
  // (held by the run and by the base of each global search), the bits of the whole grid, and
  // the outputs' grids and pictures.
  constexpr double kBytesPerCell = 8.0;
  const double cells = extent.cells.x() * extent.cells.y();
  return {.bytes = static_cast<std::uint64_t>(std::min(kBytesPerCell * cells, 1e19)),
          .driver = fmt::format("its search map of {:.0f} x {:.0f} cells of {} m (--resolution)",
                                extent.cells.x(), extent.cells.y(), map.cell_size_m())};
}

SlamResult RssMethod::Run(const Dataset& dataset, const proto::SlamParams& params,
                          const SlamHooks& hooks) const {
  std::optional<RssSlamState> resume;
  if (!hooks.resume.empty()) {
    proto::RssCheckpoint checkpoint;
    if (!checkpoint.ParseFromString(hooks.resume)) {
      throw Error("the job's checkpoint is not an rss checkpoint");
    }
    resume = RssSlamStateFromProto(checkpoint);
  }
  RssSlamRuntime runtime;
  runtime.resume = resume ? &*resume : nullptr;
  runtime.progress = hooks.progress;
  if (hooks.checkpoint) {
    runtime.checkpoint = [&hooks](const RssSlamState& state) {
      hooks.checkpoint([&state] { return ToProto(state).SerializeAsString(); });
    };
  }
  if (hooks.islands) {
    runtime.global = [&hooks](const GlobalSearchTask& task, const GlobalSearchProblem&) {
      proto::ProblemSpec spec;
      *spec.mutable_global_search() = ToProto(task);
      return hooks.islands(spec);
    };
  }
  RssSlamResult run = RunRssSlam(dataset, params, runtime);
  OccupancyGrid map =
      OccupancyGridAtPoses(dataset, run.trajectory, params.rss().map().cell_size_m());
  SlamResult result{.trajectory = std::move(run.trajectory),
                    .map = std::move(map),
                    .loops = std::move(run.loops),
                    .odometry_stalls = std::move(run.odometry_stalls),
                    .seconds = run.times.total,
                    .evaluations = run.local_evaluations + run.global_evaluations,
                    .method_report = {},
                    .pareto_fronts = {}};
  *result.method_report.mutable_rss() = RunReport(run);
  return result;
}

std::shared_ptr<const Problem> RssMethod::TaskProblem(const Dataset& dataset,
                                                      const proto::ProblemSpec& task) const {
  if (!task.has_global_search()) throw Error("an rss task names no global search");
  if (task.global_search().last() > dataset.scans.size()) {
    throw Error("a global search up to scan " + std::to_string(task.global_search().last()) +
                " of a log of " + std::to_string(dataset.scans.size()) + " scans");
  }
  auto search = std::make_shared<const GlobalSearchOnBase>(dataset, task);
  return std::shared_ptr<const Problem>(search, &search->problem);
}

std::vector<SlamFlag> RssMethod::Flags() const {
  return {
      {"--local-fitness", "rss.local.fitness",
       "local search fitness: eval1 (occupied cells, eq. 1) or eval2 (observations per occupied "
       "cell, eq. 2)",
       ""},
      {"--local-population", "rss.local.particles",
       "local search: PSO particles (the swarm's size)", "", "--particles"},
      {"--local-iterations", "rss.local.iterations", "local search: PSO iterations per scan", ""},
      {"--resolution", "rss.map.cell_size_m",
       "map cell size, metres per cell (map.yaml's resolution)", ""},
      {"--local-only", "rss.global.enabled",
       "local search alone: no loop detection, no global search", "false"},
      {"--global-every", "rss.global.every_scans",
       "K: a global search every K scans besides those on loops (0: on loops only)", ""},
      {"--partitions", "rss.global.partitions", "L: partitions of a global search's stretch", ""},
      {"--generations", "rss.global.generations", "generations of each global search", ""},
      {"--islands", "rss.global.islands", "islands of each global search", ""},
      {"--preset", "rss.global.preset",
       "the algorithm each island runs, as a paper's preset (docs/engine.md)", ""},
      {"--max-stretch", "rss.global.max_stretch_scans",
       "scans a global search covers at most (0: the whole loop, or all since the last)", ""},
      {"--loop-radius", "rss.loops.revisit_radius_m",
       "loop detection: distance from an earlier pose that counts as a revisit, m", ""},
      {"--min-match-score", "rss.loops.min_match_score",
       "loop detection: the share of a scan's returns that must match the earlier place, (0, 1]",
       ""},
  };
}

std::string RssMethod::Summary(const proto::SlamReport& report) const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  const proto::RssParams& p = report.params().rss();
  const proto::RssLocalSearch& l = p.local();
  s << "  local search: PSO of " << l.particles() << " particles x " << l.iterations()
    << " iterations on " << l.fitness() << ", map cells "
    << fmt::format("{}", p.map().cell_size_m()) << " m, "
    << (l.odometry_tie_pull() > 0 ? "ties to odometry, " : "")
    << (l.second_swarm_above_rad() > 0 ? "a second swarm at odometry's heading, " : "")
    << (l.odometry_below_information() > 0 ? "odometry where the scan fixes nothing, " : "")
    << (l.odometry_weight() > 0 ? "odometry weighted " + FormatShortest(l.odometry_weight()) + ", "
                                : "")
    << (l.free_frontier() ? "the seen space's edge free, " : "")
    << (l.refine().iterations() > 0 ? "refined below a cell" : "not refined") << "\n";
  s << "  global search: ";
  const proto::RssGlobalSearch& g = p.global();
  if (g.enabled()) {
    s << (g.every_scans() > 0 ? "on a loop or every " + std::to_string(g.every_scans()) + " steps"
                              : std::string("on a loop"))
      << ", " << g.partitions() << " partitions, "
      << (g.beam_stride() > 1 ? "1 return in " + std::to_string(g.beam_stride()) + " scored"
                              : std::string("all returns scored"))
      << ", " << g.islands() << " islands of " << g.preset() << " x " << g.generations()
      << " generations\n";
  } else {
    s << "off\n";
  }
  const proto::RssRunReport& r = report.rss();
  const proto::SlamPhaseTimes& t = r.times();
  s << "  phases: local search " << t.local_s() << " s, loop detection " << t.detection_s()
    << " s, global search " << t.global_s() << " s\n";
  s << "  fitness evaluations: " << r.local_evaluations() << " local, " << r.global_evaluations()
    << " global\n";
  int applied = 0;
  for (const proto::GlobalSearchRecord& search : r.global_searches()) applied += search.applied();
  s << "  global searches: " << r.global_searches_size() << ", " << applied << " applied\n";
  return s.str();
}

}  // namespace evoslam
