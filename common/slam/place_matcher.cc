#include "common/slam/place_matcher.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/transform/pose2_frame.h"
#include "common/util/error.h"

namespace evoslam {
namespace {

// Point loads a lattice must make before its headings are shared out among threads: the coarse
// lattice of a loop check (3 to 40 million) is, the finer ones around its best (about 10^5,
// tens of microseconds) are not.
constexpr std::size_t kMinParallelWork = std::size_t{1} << 20;

// The surface's normal at return j of one scan's returns (beam order) seen from `laser`, turned
// toward the laser: across the line through its neighbours where they lie within
// kMaxNeighbourGap, else straight back along the beam.
Eigen::Vector2d FacingNormal(std::span<const Eigen::Vector2d> returns, std::size_t j,
                             const Eigen::Vector2d& laser) {
  constexpr double kMaxNeighbourGap = 0.3;  // m: farther, the neighbours lie on another surface
  const Eigen::Vector2d& p = returns[j];
  const Eigen::Vector2d& before = returns[j > 0 ? j - 1 : j];
  const Eigen::Vector2d& after = returns[j + 1 < returns.size() ? j + 1 : j];
  const Eigen::Vector2d tangent = after - before;
  const Eigen::Vector2d beam = p - laser;
  Eigen::Vector2d normal = -beam;
  if ((before - p).norm() <= kMaxNeighbourGap && (after - p).norm() <= kMaxNeighbourGap &&
      tangent.norm() > 0.0) {
    normal = Eigen::Vector2d(-tangent.y(), tangent.x());
    if (normal.dot(beam) > 0.0) normal = -normal;
  }
  const double length = normal.norm();
  return length > 0.0 ? Eigen::Vector2d(normal / length) : Eigen::Vector2d::Zero();
}

}  // namespace

PlaceMatcher::PlaceMatcher(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                           double resolution, double sigma, double margin) {
  if (scans.size() != poses.size()) throw Error("place matcher: one pose per scan is needed");
  if (!(resolution > 0.0) || !(sigma > 0.0)) {
    throw Error("place matcher: the resolution and sigma must be positive");
  }
  scan_starts_.push_back(0);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const Pose2Frame frame(poses[k]);
    for (const Eigen::Vector2d& p : ReturnPoints(scans[k])) hits_.push_back(frame * p);
    scan_starts_.push_back(hits_.size());
    lasers_.push_back(poses[k].translation());
  }
  if (hits_.empty()) return;
  Eigen::Vector2d lo = hits_.front(), hi = hits_.front();
  for (const Eigen::Vector2d& h : hits_) {
    lo = lo.cwiseMin(h);
    hi = hi.cwiseMax(h);
  }
  const int width = static_cast<int>(std::ceil((hi.x() - lo.x() + 2 * margin) / resolution)) + 1;
  const int height = static_cast<int>(std::ceil((hi.y() - lo.y() + 2 * margin) / resolution)) + 1;
  geometry_ = GridGeometry(resolution, (lo.array() - margin).matrix(), width, height);
  field_.assign(geometry_.cell_count(), 0.0f);

  // Stamp a Gaussian around every return, keeping the nearest one's value per cell.
  const int radius = static_cast<int>(std::ceil(3.0 * sigma / resolution));
  std::vector<float> kernel;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const double d2 = (dx * dx + dy * dy) * resolution * resolution;
      kernel.push_back(static_cast<float>(std::exp(-0.5 * d2 / (sigma * sigma))));
    }
  }
  for (const Eigen::Vector2d& h : hits_) {
    const Eigen::Vector2d at = geometry_.ToCells(h);
    const int cx = static_cast<int>(std::floor(at.x()));
    const int cy = static_cast<int>(std::floor(at.y()));
    for (int dy = -radius; dy <= radius; ++dy) {
      const int y = cy + dy;
      if (y < 0 || y >= height) continue;
      for (int dx = -radius; dx <= radius; ++dx) {
        const int x = cx + dx;
        if (x < 0 || x >= width) continue;
        float& cell = field_[geometry_.Index(x, y)];
        cell = std::max(
            cell, kernel[static_cast<std::size_t>((dy + radius) * (2 * radius + 1) + dx + radius)]);
      }
    }
  }
  constexpr int k = kCoarseStepCells;
  const auto phase_width = static_cast<std::size_t>((width + k - 1) / k);
  coarse_field_.assign(k * static_cast<std::size_t>(height) * phase_width, 0.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      coarse_field_[static_cast<std::size_t>((x % k) * height + y) * phase_width +
                    static_cast<std::size_t>(x / k)] = field_[geometry_.Index(x, y)];
    }
  }
}

double PlaceMatcher::Score(std::span<const Eigen::Vector2d> points, const Pose2& pose) const {
  if (points.empty()) return 0.0;
  double sum = 0.0;
  const double c = std::cos(pose.theta()), s = std::sin(pose.theta());
  // Every score here finds cells by multiplying by the reciprocal of the resolution: cheaper in
  // these loops than GridGeometry's division, with which a point on a cell's edge may land in the
  // next cell.
  const Eigen::Vector2d& origin = geometry_.origin();
  const double inv = 1.0 / geometry_.resolution();
  for (const Eigen::Vector2d& p : points) {
    const double wx = pose.x() + c * p.x() - s * p.y();
    const double wy = pose.y() + s * p.x() + c * p.y();
    const double fx = std::floor((wx - origin.x()) * inv);
    const double fy = std::floor((wy - origin.y()) * inv);
    if (!geometry_.ContainsCells(fx, fy)) continue;
    sum += field_[geometry_.Index(static_cast<int>(fx), static_cast<int>(fy))];
  }
  return sum / static_cast<double>(points.size());
}

double PlaceMatcher::SideAgreement(std::span<const Eigen::Vector2d> points,
                                   const Pose2& pose) const {
  const Eigen::Rotation2Dd turn(pose.theta());
  const Eigen::Vector2d& origin = geometry_.origin();
  const double inv = 1.0 / geometry_.resolution();
  std::size_t near = 0, agree = 0;
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d w = pose.translation() + turn * p;
    const double fx = std::floor((w.x() - origin.x()) * inv);
    const double fy = std::floor((w.y() - origin.y()) * inv);
    if (!geometry_.ContainsCells(fx, fy)) continue;
    if (field_[geometry_.Index(static_cast<int>(fx), static_cast<int>(fy))] < kNearField) continue;
    // The nearest return by a plain scan, and its normal only now: this runs for the few matches
    // that would be loops, where keeping a normal per return or per cell would cost every loop
    // check's field.
    std::size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < hits_.size(); ++i) {
      const double d2 = (hits_[i] - w).squaredNorm();
      if (d2 < best) {
        best = d2;
        nearest = i;
      }
    }
    // The scan that holds the nearest return: the last whose first return is at or before it.
    const auto k = static_cast<std::size_t>(
        std::upper_bound(scan_starts_.begin(), scan_starts_.end(), nearest) - scan_starts_.begin() -
        1);
    const std::span<const Eigen::Vector2d> returns(hits_.data() + scan_starts_[k],
                                                   scan_starts_[k + 1] - scan_starts_[k]);
    ++near;
    if ((turn * p).dot(FacingNormal(returns, nearest - scan_starts_[k], lasers_[k])) < 0.0) {
      ++agree;
    }
  }
  return near == 0 ? 1.0 : static_cast<double>(agree) / static_cast<double>(near);
}

void PlaceMatcher::ScoreTranslations(std::span<const Eigen::Vector2d> points, const Pose2& center,
                                     double theta, double step, int half_steps,
                                     std::vector<double>& scores) const {
  const int side = 2 * half_steps + 1;
  scores.assign(static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0.0);
  const double cells_per_step = step / geometry_.resolution();
  const auto k = static_cast<int>(std::lround(cells_per_step));
  if ((k != 1 && k != kCoarseStepCells) || std::abs(cells_per_step - k) > 1e-9) {
    for (int iy = -half_steps; iy <= half_steps; ++iy) {
      for (int ix = -half_steps; ix <= half_steps; ++ix) {
        scores[static_cast<std::size_t>((iy + half_steps) * side + ix + half_steps)] =
            Score(points, Pose2(center.x() + ix * step, center.y() + iy * step, theta));
      }
    }
    return;
  }
  // A step of k whole cells moves every point by k cells, so each translation costs a point one
  // load: this is where loop detection spends its time.
  if (points.empty()) return;
  const auto floor_div = [](int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  const double c = std::cos(theta), s = std::sin(theta);
  const Eigen::Vector2d& origin = geometry_.origin();
  const double inv = 1.0 / geometry_.resolution();
  const int width = geometry_.width(), height = geometry_.height();
  const float* field = k == 1 ? field_.data() : coarse_field_.data();
  const auto phase_width = static_cast<std::size_t>((width + k - 1) / k);
  for (const Eigen::Vector2d& p : points) {
    const double fx = std::floor((center.x() + c * p.x() - s * p.y() - origin.x()) * inv);
    const double fy = std::floor((center.y() + s * p.x() + c * p.y() - origin.y()) * inv);
    // Too far off the field for any translation to bring it in (and safe to convert).
    const double reach = static_cast<double>(k) * half_steps;
    if (fx < -reach || fy < -reach || fx >= width + reach || fy >= height + reach) continue;
    const int x = static_cast<int>(fx), y = static_cast<int>(fy);
    const int ix_lo = std::max(-half_steps, -floor_div(x, k));
    const int ix_hi = std::min(half_steps, floor_div(width - 1 - x, k));
    // Cell x + k ix lies at column x / k + ix of its remainder's rows.
    const int column = floor_div(x, k);
    const float* phase = field + static_cast<std::size_t>(x - k * column) *
                                     static_cast<std::size_t>(height) * phase_width;
    for (int iy = -half_steps; iy <= half_steps; ++iy) {
      const int row = y + k * iy;
      if (row < 0 || row >= height) continue;
      const float* cells = phase + static_cast<std::size_t>(row) * phase_width;
      double* out = &scores[static_cast<std::size_t>((iy + half_steps) * side + half_steps)];
      for (int ix = ix_lo; ix <= ix_hi; ++ix) out[ix] += cells[column + ix];
    }
  }
  const double n = static_cast<double>(points.size());
  for (double& score : scores) score /= n;
}

PlaceMatcher::Match PlaceMatcher::Lattice(std::span<const Eigen::Vector2d> points,
                                          const Pose2& center, double step, int half_steps,
                                          double step_theta, int half_steps_theta, int stride,
                                          double rival_distance) const {
  std::vector<Eigen::Vector2d> used;
  for (std::size_t i = 0; i < points.size(); i += static_cast<std::size_t>(stride)) {
    used.push_back(points[i]);
  }
  // The best score per translation over all headings, for the rivals.
  const bool rivals = rival_distance > 0.0;
  const int side = 2 * half_steps + 1;
  const auto cells = static_cast<std::size_t>(side) * static_cast<std::size_t>(side);
  const int headings = 2 * half_steps_theta + 1;
  std::vector<double> best_at(rivals ? cells : 0, -1.0);
  // Each heading's best, the first in lattice order on a tie; picked in heading order below, so
  // the result does not depend on how the headings were shared out among threads.
  std::vector<Match> heading_best(static_cast<std::size_t>(headings), Match{center, -1.0});
  const bool parallel =
      used.size() * cells * static_cast<std::size_t>(headings) >= kMinParallelWork;
#pragma omp parallel if (parallel)
  {
    std::vector<double> scores;
    std::vector<double> own_best_at(best_at.size(), -1.0);
#pragma omp for schedule(static)
    for (int h = 0; h < headings; ++h) {
      const double theta = center.theta() + (h - half_steps_theta) * step_theta;
      ScoreTranslations(used, center, theta, step, half_steps, scores);
      Match& best = heading_best[static_cast<std::size_t>(h)];
      for (int iy = -half_steps; iy <= half_steps; ++iy) {
        for (int ix = -half_steps; ix <= half_steps; ++ix) {
          const auto at = static_cast<std::size_t>((iy + half_steps) * side + ix + half_steps);
          const double score = scores[at];
          if (score > best.score) {
            best = {Pose2(center.x() + ix * step, center.y() + iy * step, theta), score};
          }
          if (rivals) own_best_at[at] = std::max(own_best_at[at], score);
        }
      }
    }
    // A maximum is exact whatever the order the threads merge in.
#pragma omp critical
    for (std::size_t at = 0; at < best_at.size(); ++at) {
      best_at[at] = std::max(best_at[at], own_best_at[at]);
    }
  }
  Match best{center, -1.0};
  for (const Match& m : heading_best) {
    if (m.score > best.score) best = m;
  }
  if (rivals) {
    double rival = 0.0;
    for (int iy = -half_steps; iy <= half_steps; ++iy) {
      for (int ix = -half_steps; ix <= half_steps; ++ix) {
        const Eigen::Vector2d at(center.x() + ix * step, center.y() + iy * step);
        if ((at - best.pose.translation()).norm() < rival_distance) continue;
        rival = std::max(
            rival, best_at[static_cast<std::size_t>((iy + half_steps) * side + ix + half_steps)]);
      }
    }
    best.distinctness = best.score - rival;
  }
  return best;
}

PlaceMatcher::Match PlaceMatcher::Search(std::span<const Eigen::Vector2d> points,
                                         const Pose2& center, double window, double window_theta,
                                         double rival_distance) const {
  if (field_.empty() || points.empty()) return {center, 0.0};
  const double step = kCoarseStepCells * geometry_.resolution();
  const double step_theta = 0.0175;  // about 1 degree: a 5 m return moves 9 cm
  const Match coarse =
      Lattice(points, center, step, static_cast<int>(std::ceil(window / step)), step_theta,
              static_cast<int>(std::ceil(window_theta / step_theta)), 2, rival_distance);
  const Match fine = Lattice(points, coarse.pose, step / 4, 4, step_theta / 4, 4, 1);
  Match result = Lattice(points, fine.pose, step / 16, 4, step_theta / 16, 4, 1);
  result.distinctness = coarse.distinctness;
  return result;
}

}  // namespace evoslam
