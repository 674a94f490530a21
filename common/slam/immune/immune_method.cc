#include "common/slam/immune/immune_method.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "common/slam/immune/immune_slam.h"
#include "common/slam/immune/trajectory_window_problem.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

std::vector<std::string> ObjectiveNames(const proto::ImmuneParams& params) {
  if (ParseImmuneVariant(params.variant()) == ImmuneVariant::kDuckett) {
    return {fmt::format("f1 + {} f2 + {} f3", params.search().occupied_weight(),
                        params.search().empty_weight())};
  }
  return {"f1 consistency", "f2 occupied cells", "f3 empty cells"};
}

std::vector<ParetoFront> Fronts(const proto::ImmuneRunReport& report,
                                const proto::ImmuneParams& params) {
  const std::vector<std::string> names = ObjectiveNames(params);
  const auto rows = static_cast<Eigen::Index>(names.size());
  std::vector<ParetoFront> fronts;
  for (int w = 0; w < report.windows_size(); ++w) {
    const proto::ImmuneWindowRecord& r = report.windows(w);
    ParetoFront front{
        .label = fmt::format("window {}: scans {}-{}", w + 1, r.first_scan(), r.last_scan()),
        .objectives = names,
        .f = Eigen::MatrixXd(rows, r.front_size() / rows),
        .start = {r.start_objectives().begin(), r.start_objectives().end()},
        .chosen = r.chosen()};
    for (int i = 0; i < r.front_size(); ++i) front.f(i % rows, i / rows) = r.front(i);
    fronts.push_back(std::move(front));
  }
  return fronts;
}

}  // namespace

void ImmuneMethod::Validate(const proto::SlamParams& params) const {
  ValidateImmuneParams(params.immune());
}

std::size_t ImmuneMethod::Islands(const proto::SlamParams&) const { return 1; }

void ImmuneMethod::SetIslands(proto::SlamParams&, std::uint32_t) const {}

MemoryNeed ImmuneMethod::PeakMemory(const Dataset& dataset, const proto::SlamParams& params) const {
  const proto::EvidenceGridParams& e = params.immune().evidence();
  const std::size_t n = ScansToMap(dataset, params);
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  std::size_t beams = 0;
  for (std::size_t k = 0; k < n; ++k) {
    low = low.cwiseMin(dataset.scans[k].pose.translation());
    high = high.cwiseMax(dataset.scans[k].pose.translation());
    beams += dataset.scans[k].ranges.size();
  }
  if (n == 0) low = high = Eigen::Vector2d::Zero();
  // The grid covers the path widened by the range cut, with room for the corrections.
  const Eigen::Vector2d extent = (high - low).array() + 2.0 * (e.max_range_m() + kImmuneGridRoom);
  const double cells =
      std::ceil(extent.x() / e.cell_size_m()) * std::ceil(extent.y() / e.cell_size_m());
  // Per cell: the map, the empty base of immune selection's local grids, and an overlay's scratch
  // per thread; per beam: its prepared end point and samples.
  constexpr double kBytesPerCell = 48.0;
  constexpr double kBytesPerBeam = 64.0;
  const double bytes = kBytesPerCell * cells + kBytesPerBeam * static_cast<double>(beams);
  return {.bytes = static_cast<std::uint64_t>(std::min(bytes, 1e19)),
          .driver = fmt::format("its evidence grid of {:.0f} x {:.0f} cells of {} m",
                                std::ceil(extent.x() / e.cell_size_m()),
                                std::ceil(extent.y() / e.cell_size_m()), e.cell_size_m())};
}

SlamResult ImmuneMethod::Run(const Dataset& dataset, const proto::SlamParams& params,
                             const SlamHooks& hooks) const {
  const std::size_t n = ScansToMap(dataset, params);
  std::vector<Pose2> initial;
  initial.reserve(n);
  for (std::size_t k = 0; k < n; ++k) initial.push_back(dataset.scans[k].pose);
  std::optional<proto::ImmuneCheckpoint> resume;
  if (!hooks.resume.empty()) {
    resume.emplace();
    if (!resume->ParseFromString(hooks.resume)) {
      throw Error("the job's checkpoint is not an immune checkpoint");
    }
  }
  ImmuneSlamRuntime runtime;
  runtime.progress = hooks.progress;
  runtime.resume = resume ? &*resume : nullptr;
  if (hooks.checkpoint) {
    runtime.checkpoint = [&hooks](const proto::ImmuneCheckpoint& state) {
      hooks.checkpoint([&state] { return state.SerializeAsString(); });
    };
  }
  ImmuneSlamResult run = RunImmuneSlam(dataset, initial, params.immune(), params.seed(), runtime);
  std::vector<StampedPose> trajectory;
  trajectory.reserve(n);
  for (std::size_t k = 0; k < n; ++k)
    trajectory.push_back({dataset.scans[k].timestamp, run.poses[k]});
  // The map drawn as every method's is, from the scans at the poses: the evidence grid's own
  // classes mark every cell a return reached as occupied (immune.evidence.count_above).
  OccupancyGrid map =
      OccupancyGridAtPoses(dataset, trajectory, params.immune().evidence().cell_size_m());
  SlamResult result{.trajectory = std::move(trajectory),
                    .map = std::move(map),
                    .loops = {},
                    .odometry_stalls = {},
                    .seconds = run.seconds,
                    .evaluations = run.evaluations,
                    .method_report = {},
                    .pareto_fronts = Fronts(run.report, params.immune())};
  *result.method_report.mutable_immune() = std::move(run.report);
  return result;
}

std::shared_ptr<const Problem> ImmuneMethod::TaskProblem(const Dataset&,
                                                         const proto::ProblemSpec&) const {
  throw Error("the immune method runs its searches in the coordinator and sends no tasks");
}

std::vector<SlamFlag> ImmuneMethod::Flags() const {
  return {
      {"--variant", "immune.variant",
       "immune method: immune (004), moea (without vaccination and immune selection) or duckett "
       "(Duckett's GA on a weighted sum)",
       ""},
      {"--window-segments", "immune.search.window_segments",
       "immune method: segments optimised at once (0: the whole trajectory)", ""},
      {"--population", "immune.search.population", "immune method: candidates per generation", ""},
      {"--max-generations", "immune.search.generations",
       "immune method: generations of each window's search at most", ""},
      {"--encoding", "immune.segments.encoding",
       "immune method: corrections as whole units (integer, 004) or continuous", ""},
      {"--evidence-cell", "immune.evidence.cell_size_m",
       "immune method: side of an evidence grid cell, m", ""},
  };
}

std::string ImmuneMethod::Summary(const proto::SlamReport& report) const {
  const proto::ImmuneParams& p = report.params().immune();
  const proto::ImmuneRunReport& r = report.immune();
  std::uint64_t generations = 0;
  std::uint32_t restarts = 0;
  for (const proto::ImmuneWindowRecord& w : r.windows()) {
    generations += w.generations();
    restarts += w.restarts();
  }
  std::ostringstream s;
  s << "  search: " << p.variant() << ", population " << p.search().population() << ", "
    << p.segments().encoding() << " corrections within +-" << p.segments().max_length_correction_m()
    << " m and +-" << p.segments().max_turn_correction_deg() << " deg a segment\n";
  s << "  trajectory: " << r.segments() << " segments, " << r.key_points() << " key points, "
    << r.windows_size() << " windows, " << generations << " generations, " << restarts
    << " restarts\n";
  if (r.start_objectives_size() == 3 && r.objectives_size() == 3) {
    s << fmt::format(
        "  evidence grid: f1 {:.1f} -> {:.1f}, occupied cells {:.0f} -> {:.0f}, empty cells "
        "{:.0f} -> {:.0f}\n",
        r.start_objectives(0), r.objectives(0), r.start_objectives(1), r.objectives(1),
        r.start_objectives(2), r.objectives(2));
  }
  return s.str();
}

}  // namespace evoslam
