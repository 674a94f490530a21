#include "common/slam/global_search_problem.h"

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

void ValidateGlobalSearchParams(const GlobalSearchParams& p) {
  if (p.partitions == 0 || p.partitions > kMaxPartitions)
    throw Error("global search: the partitions must number from 1 to " +
                std::to_string(kMaxPartitions));
  if (!(p.max_error.array() >= 0.0).all() || !p.max_error.allFinite())
    throw Error("global search: the maximum partition error must be finite and not negative");
  if (!(p.sigma.array() > 0.0).all() || !p.sigma.allFinite())
    throw Error("global search: the Gaussian widths must be positive");
  if (!(p.w1 >= 0.0) || !(p.w2 >= 0.0)) throw Error("global search: weights must be >= 0");
  if (p.beam_stride == 0) throw Error("global search: the beam stride must be >= 1");
}

double WeightedLength(const Eigen::Vector2d& miss, double heading, const Eigen::Matrix2d& weight) {
  if (weight.isIdentity(0.0)) return miss.norm();
  const Eigen::Vector2d local = Eigen::Rotation2Dd(-heading) * miss;
  return std::sqrt(std::max(0.0, local.dot(weight * local)));
}

GlobalSearchProblem::GlobalSearchProblem(std::span<const LaserScan> scans,
                                         std::span<const Pose2> poses, std::size_t first,
                                         std::size_t last, const HitCountGrid& base,
                                         const GlobalSearchParams& params,
                                         std::optional<LoopConstraint> loop,
                                         std::span<const LoopConstraint> held)
    : base_(base), params_(params), loop_(loop), first_(first), last_(last) {
  ValidateGlobalSearchParams(params);
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
  const std::size_t partitions = std::max<std::size_t>(1, std::min(params.partitions, steps));
  for (std::size_t i = 0; i <= partitions; ++i) bounds_.push_back(i * steps / partitions);
  if (params.scored_scans > 0) {
    scan_stride_ =
        std::max<std::size_t>(1, (last - first + params.scored_scans - 1) / params.scored_scans);
  }
  for (std::size_t k = first; k < last; k += scan_stride_) {
    const std::vector<Eigen::Vector2d> all = ReturnPoints(scans[k]);
    std::vector<Eigen::Vector2d>& used = returns_.emplace_back();
    for (std::size_t i = 0; i < all.size(); i += params.beam_stride) used.push_back(all[i]);
  }
  if (loop) observed_.push_back(Observe(scans, poses, *loop));
  for (const LoopConstraint& h : held) observed_.push_back(Observe(scans, poses, h));
  const auto n = static_cast<Eigen::Index>(partitions * kGenesPerColumn);
  lower_.resize(n);
  upper_.resize(n);
  for (std::size_t i = 0; i < partitions; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const auto g = static_cast<Eigen::Index>(i * kGenesPerColumn + 2 * axis);
      lower_(g) = -params.max_error(axis);
      upper_(g) = params.max_error(axis);
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
  // The loops the candidate closes: the search's own, first, and the held loops whose earlier
  // scan the stretch does not move.
  std::vector<const Observation*> closed;
  for (const Observation& o : observed_) {
    if (o.constraint.earlier < first_) closed.push_back(&o);
  }
  const auto m = static_cast<Eigen::Index>(closed.size());
  const std::size_t partitions = bounds_.size() - 1;
  const auto columns = static_cast<Eigen::Index>(partitions);
  Eigen::VectorXd x = Identity();
  const auto gene = [&](std::size_t partition, int axis) {
    return static_cast<Eigen::Index>(partition * kGenesPerColumn + 2 * axis);
  };
  const auto clamp = [&](Eigen::Index g, double v) { return std::clamp(v, lower_(g), upper_(g)); };
  const auto laters = [&](const Eigen::VectorXd& candidate) {
    const std::vector<Pose2> poses = Apply(candidate);
    std::vector<Pose2> at;
    for (const Observation* o : closed) at.push_back(poses[o->constraint.later - first_]);
    return at;
  };
  std::vector<Pose2> expected;
  for (const Observation* o : closed) expected.push_back(o->earlier_pose * o->constraint.relative);
  // The heading errors add up along the path: a later heading moves by each partition's error
  // times the share of its weight spent before the later scan. When the search's loop alone is
  // closed and ends the stretch (as RunRssSlam's do) that is all of it, and the least-norm split
  // is the even one.
  const std::vector<Pose2> start = laters(x);
  Eigen::VectorXd turn(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    turn(k) = WrapAngle(expected[k].theta() - start[k].theta());
  }
  Eigen::MatrixXd turns = Eigen::MatrixXd::Ones(m, columns);
  if (m > 1 || loop_->later + 1 < last_) {
    for (std::size_t i = 0; i < partitions; ++i) {
      Eigen::VectorXd unit = x;
      unit(gene(i, 2)) += 1.0;
      const std::vector<Pose2> turned = laters(unit);
      for (Eigen::Index k = 0; k < m; ++k) {
        turns(k, static_cast<Eigen::Index>(i)) = WrapAngle(turned[k].theta() - start[k].theta());
      }
    }
  }
  if (m == 1) {
    const double reach = turns.row(0).squaredNorm();
    for (std::size_t i = 0; i < partitions && reach > 0; ++i) {
      x(gene(i, 2)) = clamp(gene(i, 2), turn(0) * turns(0, static_cast<Eigen::Index>(i)) / reach);
    }
  } else {
    const Eigen::VectorXd errors = turns.completeOrthogonalDecomposition().solve(turn);
    for (std::size_t i = 0; i < partitions; ++i) {
      x(gene(i, 2)) = clamp(gene(i, 2), errors(static_cast<Eigen::Index>(i)));
    }
  }
  // With the headings set, the later positions move linearly with the position errors: each
  // partition's two columns of that map, then the least-norm (or, when the loops ask more than
  // the partitions can give, least-squares) errors that make up the misses.
  const std::vector<Pose2> at = laters(x);
  Eigen::MatrixXd moves(2 * m, 2 * columns);
  for (std::size_t i = 0; i < partitions; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      Eigen::VectorXd unit = x;
      unit(gene(i, axis)) += 1.0;
      const std::vector<Pose2> moved = laters(unit);
      for (Eigen::Index k = 0; k < m; ++k) {
        moves.block<2, 1>(2 * k, static_cast<Eigen::Index>(2 * i) + axis) =
            moved[k].translation() - at[k].translation();
      }
    }
  }
  Eigen::VectorXd miss(2 * m);
  for (Eigen::Index k = 0; k < m; ++k) {
    miss.segment<2>(2 * k) = expected[k].translation() - at[k].translation();
  }
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
        const double d = (t - gene(axis, 1)) / params_.sigma(axis);
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
  double distance = 0.0;
  for (const Observation& o : observed_) distance += Distance(o, poses);
  fitness[1] = params_.w1 * conflicts + params_.w2 * distance;
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
  return std::hypot(WeightedLength(later.translation() - expected.translation(),
                                   earlier.pose().theta(), c.weight),
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
                   double min_eq6_gain, double min_eq7_gain) {
  return after[0] < before[0] - min_eq6_gain * std::abs(before[0]) ||
         after[1] < (1.0 - min_eq7_gain) * before[1];
}

}  // namespace evoslam
