#include "common/slam/immune/trajectory_window_problem.h"

#include <algorithm>
#include <string>

#include "common/slam/immune/key_point_immunity.h"
#include "common/util/error.h"
#include "common/util/infinity.h"

namespace evoslam {

ImmuneVariant ParseImmuneVariant(std::string_view name) {
  if (name == "immune") return ImmuneVariant::kImmune;
  if (name == "moea") return ImmuneVariant::kMoea;
  if (name == "duckett") return ImmuneVariant::kDuckett;
  throw Error("immune.variant must be immune, moea or duckett, not '" + std::string(name) + "'");
}

double DuckettSum(double consistency, double occupied, double empty,
                  const proto::ImmuneSearchParams& search) {
  return consistency + search.occupied_weight() * occupied + search.empty_weight() * empty;
}

TrajectoryWindowProblem::TrajectoryWindowProblem(TrajectoryWindow window,
                                                 const proto::ImmuneParams& params)
    : window_(std::move(window)),
      variant_(ParseImmuneVariant(params.variant())),
      search_(params.search()),
      scan_stride_(params.scan_stride()),
      genes_(params.segments(), window_.segments,
             variant_ == ImmuneVariant::kImmune ? window_.key_points.size() : 0),
      empty_(window_.base->geometry(), params.evidence()) {
  const auto& segments = window_.trajectory->segments();
  if (window_.segments == 0 || window_.first_segment + window_.segments > segments.size()) {
    throw Error("a window of " + std::to_string(window_.segments) + " segments from segment " +
                std::to_string(window_.first_segment) + " of " + std::to_string(segments.size()));
  }
  if (window_.scans.size() != window_.trajectory->scans()) {
    throw Error("a window's problem needs one prepared scan per scan of the trajectory");
  }
  if (variant_ == ImmuneVariant::kImmune) {
    immunity_ = std::make_unique<KeyPointImmunity>(*this, params.key_points().cell_size_m(),
                                                   search_.accept_worse());
  }
}

TrajectoryWindowProblem::~TrajectoryWindowProblem() = default;

std::size_t TrajectoryWindowProblem::objectives() const {
  return variant_ == ImmuneVariant::kDuckett ? 1 : 3;
}

std::vector<Eigen::VectorXd> TrajectoryWindowProblem::starts() const {
  return {Eigen::VectorXd::Zero(static_cast<Eigen::Index>(genes_.dimension()))};
}

const Immunity* TrajectoryWindowProblem::immunity() const { return immunity_.get(); }

std::size_t TrajectoryWindowProblem::first_scan() const {
  return window_.trajectory->segments()[window_.first_segment].first;
}

std::size_t TrajectoryWindowProblem::last_scan() const {
  return window_.trajectory->segments()[window_.first_segment + window_.segments - 1].last;
}

void TrajectoryWindowProblem::Poses(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    std::span<Pose2> out) const {
  std::vector<SegmentCorrection> corrections(window_.segments);
  genes_.Corrections(x, corrections);
  window_.trajectory->Poses(window_.first_segment, corrections, window_.from, out);
}

EvidenceObjectives TrajectoryWindowProblem::Score(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                  EvidenceOverlay& overlay,
                                                  std::vector<Pose2>& poses,
                                                  std::vector<PlacedScan>& placed) const {
  Poses(x, poses);
  // A candidate that carries scans off the grid is infeasible: readings that fall outside count
  // nowhere, so every objective would reward throwing them off.
  const GridGeometry& g = window_.base->geometry();
  const double reach = window_.base->params().max_range_m();
  const Eigen::Vector2d low = g.origin().array() + reach;
  const Eigen::Vector2d high = g.max_corner().array() - reach;
  for (const Pose2& pose : poses) {
    const Eigen::Vector2d p = pose.translation();
    if (!(p.x() >= low.x() && p.y() >= low.y() && p.x() <= high.x() && p.y() <= high.y())) {
      return {.consistency = kInfinity, .occupied = 0, .empty = 0};
    }
  }
  placed.clear();
  const std::size_t first = first_scan();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if ((first + k) % scan_stride_ == 0) placed.push_back({&window_.scans[first + k], poses[k]});
  }
  return overlay.Score({}, placed);
}

EvidenceObjectives TrajectoryWindowProblem::Objectives(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  EvidenceOverlay overlay(*window_.base);
  std::vector<Pose2> poses(last_scan() - first_scan() + 1);
  std::vector<PlacedScan> placed;
  return Score(x, overlay, poses, placed);
}

double TrajectoryWindowProblem::LocalConsistency(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                 std::size_t first) const {
  const auto& segments = window_.trajectory->segments();
  const std::size_t last = std::min(first + 1, window_.segments - 1);
  std::vector<Pose2> poses(last_scan() - first_scan() + 1);
  Poses(x, poses);
  std::vector<PlacedScan> placed;
  const std::size_t from = segments[window_.first_segment + first].first;
  const std::size_t to = segments[window_.first_segment + last].last;
  for (std::size_t k = from; k <= to; ++k) {
    if (k % scan_stride_ == 0) placed.push_back({&window_.scans[k], poses[k - first_scan()]});
  }
  EvidenceOverlay overlay(empty_);
  return overlay.Score({}, placed).consistency;
}

void TrajectoryWindowProblem::WriteFitness(const EvidenceObjectives& o,
                                           std::span<double> out) const {
  if (o.consistency == kInfinity) {  // off the grid (Score)
    std::fill(out.begin(), out.end(), kInfinity);
    return;
  }
  if (variant_ == ImmuneVariant::kDuckett) {
    out[0] = DuckettSum(o.consistency, static_cast<double>(o.occupied),
                        static_cast<double>(o.empty), search_);
    return;
  }
  out[0] = o.consistency;
  out[1] = static_cast<double>(o.occupied);
  out[2] = static_cast<double>(o.empty);
}

void TrajectoryWindowProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                                       std::span<double> fitness) const {
  const Eigen::Index n = candidates.cols();
  const std::size_t m = objectives();
#pragma omp parallel
  {
    EvidenceOverlay overlay(*window_.base);
    std::vector<Pose2> poses(last_scan() - first_scan() + 1);
    std::vector<PlacedScan> placed;
#pragma omp for schedule(dynamic, 1)
    for (Eigen::Index i = 0; i < n; ++i) {
      const EvidenceObjectives o = Score(candidates.col(i), overlay, poses, placed);
      WriteFitness(o, fitness.subspan(static_cast<std::size_t>(i) * m, m));
    }
  }
}

}  // namespace evoslam
