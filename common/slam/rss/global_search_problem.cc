#include "common/slam/rss/global_search_problem.h"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

constexpr std::size_t kGenesPerColumn = 6;  // (error, mean) for x, y and theta

}  // namespace

Eigen::Vector3d PartitionErrorBounds(const GlobalSearchParams& params) {
  return {params.max_error_x_m(), params.max_error_y_m(), params.max_error_theta_rad()};
}

Eigen::Vector3d RefineBounds(const GlobalSearchParams& params) {
  return {params.refine_bound_x_m(), params.refine_bound_y_m(), params.refine_bound_theta_rad()};
}

Eigen::Vector3d GaussianWidths(const GlobalSearchParams& params) {
  return {params.spread_x(), params.spread_y(), params.spread_theta()};
}

void ValidateGlobalSearchParams(const GlobalSearchParams& p) {
  if (p.partitions() == 0 || p.partitions() > kMaxPartitions)
    throw Error("global.partitions: from 1 to " + std::to_string(kMaxPartitions));
  const Eigen::Vector3d bounds = PartitionErrorBounds(p);
  if (!(bounds.array() >= 0.0).all() || !bounds.allFinite())
    throw Error("global.max_error_*: must be finite and not negative");
  const Eigen::Vector3d widths = GaussianWidths(p);
  if (!(widths.array() > 0.0).all() || !widths.allFinite())
    throw Error("global.spread_*: must be finite and positive");
  if (!(p.occupied_pose_weight() >= 0.0) || !(p.loop_miss_weight() >= 0.0) ||
      !std::isfinite(p.occupied_pose_weight()) || !std::isfinite(p.loop_miss_weight()))
    throw Error("global.occupied_pose_weight and global.loop_miss_weight: must be finite, >= 0");
  if (p.beam_stride() == 0) throw Error("global.beam_stride: must be >= 1");
}

GlobalSearchProblem::GlobalSearchProblem(std::span<const LaserScan> scans,
                                         std::span<const Pose2> poses, std::size_t first,
                                         std::size_t last, const HitCountGrid& base,
                                         const GlobalSearchParams& params,
                                         const Eigen::Vector3d& max_error,
                                         std::optional<LoopConstraint> loop)
    : base_(base),
      widths_(GaussianWidths(params)),
      occupied_pose_weight_(params.occupied_pose_weight()),
      loop_miss_weight_(params.loop_miss_weight()),
      loop_(loop),
      first_(first),
      last_(last) {
  ValidateGlobalSearchParams(params);
  if (!(max_error.array() >= 0.0).all() || !max_error.allFinite())
    throw Error("global search: the partitions' error bounds must be finite and not negative");
  if (!(first < last) || last > scans.size() || last > poses.size()) {
    throw Error("global search: scans [" + std::to_string(first) + ", " + std::to_string(last) +
                ") do not fit a log of " + std::to_string(scans.size()) + " scans and " +
                std::to_string(poses.size()) + " poses");
  }
  steps_begin_ = std::max<std::size_t>(first, 1);
  anchor_ = Pose2Frame(poses[steps_begin_ - 1]);
  for (std::size_t j = steps_begin_; j < last; ++j)
    increments_.emplace_back(poses[j - 1].inverse() * poses[j]);
  const std::size_t steps = increments_.size();
  const std::size_t partitions =
      std::max<std::size_t>(1, std::min<std::size_t>(params.partitions(), steps));
  for (std::size_t i = 0; i <= partitions; ++i) bounds_.push_back(i * steps / partitions);
  if (const std::size_t scored = params.scored_scans(); scored > 0) {
    scan_stride_ = std::max<std::size_t>(1, (last - first + scored - 1) / scored);
  }
  for (std::size_t k = first; k < last; k += scan_stride_) {
    const std::vector<Eigen::Vector2d> all = ReturnPoints(scans[k]);
    std::vector<Eigen::Vector2d>& used = returns_.emplace_back();
    for (std::size_t i = 0; i < all.size(); i += params.beam_stride()) used.push_back(all[i]);
  }
  if (loop) observed_ = Observe(scans, poses, *loop);
  const auto n = static_cast<Eigen::Index>(partitions * kGenesPerColumn);
  lower_.resize(n);
  upper_.resize(n);
  for (std::size_t i = 0; i < partitions; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const auto g = static_cast<Eigen::Index>(i * kGenesPerColumn + 2 * axis);
      lower_(g) = -max_error(axis);
      upper_(g) = max_error(axis);
      lower_(g + 1) = 0.0;
      upper_(g + 1) = 1.0;
    }
  }
}

Eigen::VectorXd GlobalSearchProblem::Identity() const {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(lower_.size());
  for (Eigen::Index g = 1; g < x.size(); g += 2) x(g) = 0.5;
  return x;
}

std::optional<Eigen::VectorXd> GlobalSearchProblem::ClosingCandidate() const {
  // A loop that starts inside the stretch bends with it; RunRssSlam's never does.
  if (!loop_ || loop_->earlier >= first_) return std::nullopt;
  const Observation& o = *observed_;
  const std::size_t partitions = bounds_.size() - 1;
  const auto columns = static_cast<Eigen::Index>(partitions);
  Eigen::VectorXd x = Identity();
  const auto gene = [&](std::size_t partition, int axis) {
    return static_cast<Eigen::Index>(partition * kGenesPerColumn + 2 * axis);
  };
  const auto clamp = [&](Eigen::Index g, double v) { return std::clamp(v, lower_(g), upper_(g)); };
  const auto later = [&](const Eigen::VectorXd& candidate) {
    return Apply(candidate)[o.constraint.later - first_];
  };
  const Pose2 expected = o.earlier_pose * o.constraint.relative;
  // The heading errors add up along the path: the later heading moves by each partition's error
  // times the share of its weight spent before the later scan. When the loop ends the stretch (as
  // RunRssSlam's do) that is all of it, and the least-norm split is the even one.
  const Pose2 start = later(x);
  const double turn = WrapAngle(expected.theta() - start.theta());
  Eigen::MatrixXd turns = Eigen::MatrixXd::Ones(1, columns);
  if (loop_->later + 1 < last_) {
    for (std::size_t i = 0; i < partitions; ++i) {
      Eigen::VectorXd unit = x;
      unit(gene(i, 2)) += 1.0;
      turns(0, static_cast<Eigen::Index>(i)) = WrapAngle(later(unit).theta() - start.theta());
    }
  }
  const double reach = turns.row(0).squaredNorm();
  for (std::size_t i = 0; i < partitions && reach > 0; ++i) {
    x(gene(i, 2)) = clamp(gene(i, 2), turn * turns(0, static_cast<Eigen::Index>(i)) / reach);
  }
  // With the heading set, the later position moves linearly with the position errors: each
  // partition's two columns of that map, then the least-norm errors that make up the miss.
  const Pose2 at = later(x);
  Eigen::MatrixXd moves(2, 2 * columns);
  for (std::size_t i = 0; i < partitions; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      Eigen::VectorXd unit = x;
      unit(gene(i, axis)) += 1.0;
      moves.block<2, 1>(0, static_cast<Eigen::Index>(2 * i) + axis) =
          later(unit).translation() - at.translation();
    }
  }
  Eigen::VectorXd miss(2);
  miss.segment<2>(0) = expected.translation() - at.translation();
  const Eigen::VectorXd errors = moves.completeOrthogonalDecomposition().solve(miss);
  for (std::size_t i = 0; i < partitions; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      x(gene(i, axis)) = clamp(gene(i, axis), errors(static_cast<Eigen::Index>(2 * i) + axis));
    }
  }
  return x;
}

std::vector<Eigen::VectorXd> GlobalSearchProblem::starts() const {
  std::vector<Eigen::VectorXd> starts{Identity()};
  if (std::optional<Eigen::VectorXd> closing = ClosingCandidate()) {
    starts.push_back(std::move(*closing));
  }
  return starts;
}

std::vector<Pose2> GlobalSearchProblem::Apply(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  std::vector<double> weights;
  std::vector<Pose2Frame> frames;
  Apply(x, weights, frames);
  std::vector<Pose2> poses;
  for (const Pose2Frame& frame : frames) poses.push_back(frame.pose());
  return poses;
}

void GlobalSearchProblem::Apply(const Eigen::Ref<const Eigen::VectorXd>& x,
                                std::vector<double>& weights,
                                std::vector<Pose2Frame>& poses) const {
  poses.clear();
  poses.reserve(last_ - first_);
  if (first_ < steps_begin_) poses.push_back(anchor_);  // scan 0 stays where it is
  // Each pose's cosine and sine serve twice: to compose the next step, and to score its scan.
  Pose2Frame pose = anchor_;
  for (std::size_t i = 0; i + 1 < bounds_.size(); ++i) {
    const std::size_t b = bounds_[i], e = bounds_[i + 1];
    const double n = static_cast<double>(e - b);
    const auto gene = [&](int axis, int which) {  // which: 0 the error, 1 the mean
      return x(static_cast<Eigen::Index>(i * kGenesPerColumn + 2 * axis + which));
    };
    // Eq. 5's Gaussian over the partition, normalised: the partition's error is spread, not
    // multiplied. The weights are kept for the second pass, so each costs one exp.
    weights.clear();
    Eigen::Vector3d weight_sum = Eigen::Vector3d::Zero();
    for (std::size_t j = b; j < e; ++j) {
      const double t = (static_cast<double>(j - b) + 0.5) / n;
      for (int axis = 0; axis < 3; ++axis) {
        const double d = (t - gene(axis, 1)) / widths_(axis);
        weights.push_back(std::exp(-0.5 * d * d));
        weight_sum(axis) += weights.back();
      }
    }
    for (std::size_t j = b; j < e; ++j) {
      const double* weight = &weights[3 * (j - b)];
      Eigen::Vector3d error;
      for (int axis = 0; axis < 3; ++axis) {
        error(axis) = weight_sum(axis) > 0 ? gene(axis, 0) * weight[axis] / weight_sum(axis) : 0.0;
      }
      pose = Pose2Frame(pose * (increments_[j] * Pose2(error(0), error(1), error(2))));
      poses.push_back(pose);
    }
  }
}

void GlobalSearchProblem::Score(const Eigen::Ref<const Eigen::VectorXd>& x, Scratch& scratch,
                                double* fitness) const {
  Apply(x, scratch.weights, scratch.poses);
  const std::vector<Pose2Frame>& poses = scratch.poses;
  GridCellSet& cells = scratch.cells;
  cells.Clear();
  HitCountGrid::Insertion added;
  for (std::size_t k = 0; k < poses.size(); k += scan_stride_) {
    base_.CountInsertion(poses[k], returns_[k / scan_stride_], cells, added);
  }
  const double occupied = static_cast<double>(base_.occupied() + added.fresh);
  fitness[0] = occupied > 0 ? -static_cast<double>(base_.total() + added.inside) / occupied : 0.0;

  // Eq. 7: path cells on obstacles, and the loop's two observations of one place.
  double conflicts = 0.0;
  for (const Pose2Frame& pose : poses) {
    const auto c = base_.CellIndex(pose.pose().translation());
    if (c) conflicts += base_.occupied(*c) || cells.Contains(*c);
  }
  const double distance = observed_ ? Distance(*observed_, poses) : 0.0;
  fitness[1] = occupied_pose_weight_ * conflicts + loop_miss_weight_ * distance;
}

GlobalSearchProblem::Observation GlobalSearchProblem::Observe(std::span<const LaserScan> scans,
                                                              std::span<const Pose2> poses,
                                                              const LoopConstraint& loop) const {
  if (loop.earlier >= loop.later || loop.later < first_ || loop.later >= last_) {
    throw Error("global search: the loop from scan " + std::to_string(loop.later) + " back to " +
                std::to_string(loop.earlier) + " must end inside the scans searched, [" +
                std::to_string(first_) + ", " + std::to_string(last_) + "), after it starts");
  }
  Observation o{.constraint = loop, .earlier_pose = {}, .lever = 0.0};
  if (loop.earlier < first_) o.earlier_pose = Pose2Frame(poses[loop.earlier]);
  const std::vector<Eigen::Vector2d> later = ReturnPoints(scans[loop.later]);
  double squares = 0.0;
  for (const Eigen::Vector2d& p : later) squares += p.squaredNorm();
  if (!later.empty()) o.lever = std::sqrt(squares / static_cast<double>(later.size()));
  return o;
}

double GlobalSearchProblem::Distance(const Observation& o,
                                     std::span<const Pose2Frame> poses) const {
  const LoopConstraint& c = o.constraint;
  const Pose2Frame& earlier = c.earlier < first_ ? o.earlier_pose : poses[c.earlier - first_];
  const Pose2 expected = earlier * c.relative;
  const Pose2& later = poses[c.later - first_].pose();
  return std::hypot((later.translation() - expected.translation()).norm(),
                    o.lever * WrapAngle(later.theta() - expected.theta()));
}

void GlobalSearchProblem::Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                                   std::span<double> fitness) const {
  const Eigen::Index n = candidates.cols();
#pragma omp parallel
  {
    Scratch scratch{GridCellSet(static_cast<std::size_t>(base_.width()) *
                                static_cast<std::size_t>(base_.height())),
                    {},
                    {}};
#pragma omp for schedule(dynamic, 1)
    for (Eigen::Index i = 0; i < n; ++i) {
      Score(candidates.col(i), scratch, fitness.data() + 2 * static_cast<std::size_t>(i));
    }
  }
}

std::optional<std::size_t> PickGlobalSolution(const Eigen::MatrixXd& fitness, double max_first) {
  // The lowest second objective, ties going to the lower first, lies on the first front: nothing
  // can dominate it.
  std::optional<std::size_t> best;
  for (Eigen::Index i = 0; i < fitness.cols(); ++i) {
    if (!(fitness(0, i) <= max_first)) continue;
    const auto b = static_cast<Eigen::Index>(best.value_or(0));
    if (!best || fitness(1, i) < fitness(1, b) ||
        (fitness(1, i) == fitness(1, b) && fitness(0, i) < fitness(0, b))) {
      best = static_cast<std::size_t>(i);
    }
  }
  return best;
}

bool WorthApplying(std::span<const double, 2> before, std::span<const double, 2> after,
                   double min_eq6_gain) {
  return after[0] < before[0] - min_eq6_gain * std::abs(before[0]) || after[1] < before[1];
}

}  // namespace evoslam
