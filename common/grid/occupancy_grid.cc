#include "common/grid/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/grid/distance_transform.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"
#include "common/util/infinity.h"

namespace evoslam {
namespace {

double Logit(double p) { return std::log(p / (1.0 - p)); }

const double kHitLogOdds = Logit(kHitProbability);
const double kMissLogOdds = Logit(kMissProbability);
const double kOccupiedLogOdds = Logit(kOccupiedThreshold);
const double kFreeLogOdds = Logit(kFreeThreshold);

// Clips the segment from + s * d, s in [s0, s1], to the box [0, w] x [0, h]. Returns false when
// nothing of it lies in the box.
bool ClipToBox(const Eigen::Vector2d& from, const Eigen::Vector2d& d, double w, double h,
               double& s0, double& s1) {
  const double size[2] = {w, h};
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (from[axis] < 0.0 || from[axis] > size[axis]) return false;
      continue;
    }
    const double a = (0.0 - from[axis]) / d[axis];
    const double b = (size[axis] - from[axis]) / d[axis];
    s0 = std::max(s0, std::min(a, b));
    s1 = std::min(s1, std::max(a, b));
  }
  return s0 <= s1;
}

// Index of the cell holding coordinate v (in cells), clamped into [0, n - 1] so that points a
// rounding error outside the grid still map to its border cells.
int ClampedCell(double v, int n) {
  return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1)));
}

// A segment clipped to a grid, in cell units: the cells it starts and ends in, and whether its
// end point itself lies on the grid.
struct GridSegment {
  Eigen::Vector2d from;
  Eigen::Vector2d delta;  // to - from
  int start_x, start_y, end_x, end_y;
  bool ends_inside;
};

std::optional<GridSegment> ClipToGrid(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                      int width, int height) {
  if (!to.allFinite()) return std::nullopt;
  const Eigen::Vector2d d = to - from;
  double s0 = 0.0;
  double s1 = 1.0;
  if (!ClipToBox(from, d, width, height, s0, s1)) return std::nullopt;
  const Eigen::Vector2d end_cell = to.array().floor();
  const Eigen::Vector2d a = from + s0 * d;
  const Eigen::Vector2d b = from + s1 * d;
  return GridSegment{from,
                     d,
                     ClampedCell(a.x(), width),
                     ClampedCell(a.y(), height),
                     ClampedCell(b.x(), width),
                     ClampedCell(b.y(), height),
                     s1 == 1.0 && end_cell.x() >= 0.0 && end_cell.x() < width &&
                         end_cell.y() >= 0.0 && end_cell.y() < height};
}

// Calls visit(x, y) for every cell the segment crosses, in order, from its start cell to its end
// cell (Amanatides-Woo). Counting the steps left on each axis makes the walk end exactly on the
// end cell whatever the rounding of the crossing parameters.
template <typename Visit>
void ForEachCell(const GridSegment& segment, Visit visit) {
  int x = segment.start_x;
  int y = segment.start_y;
  const int step_x = segment.end_x >= x ? 1 : -1;
  const int step_y = segment.end_y >= y ? 1 : -1;
  int left_x = std::abs(segment.end_x - x);
  int left_y = std::abs(segment.end_y - y);
  const auto crossing = [](int cell, int step, double start, double delta) {
    return (cell + (step > 0 ? 1 : 0) - start) / delta;
  };
  const Eigen::Vector2d& from = segment.from;
  const Eigen::Vector2d& d = segment.delta;
  double next_x = left_x > 0 ? crossing(x, step_x, from.x(), d.x()) : kInfinity;
  double next_y = left_y > 0 ? crossing(y, step_y, from.y(), d.y()) : kInfinity;
  visit(x, y);
  while (left_x + left_y > 0) {
    if (left_y == 0 || (left_x > 0 && next_x < next_y)) {
      x += step_x;
      --left_x;
      next_x = left_x > 0 ? crossing(x, step_x, from.x(), d.x()) : kInfinity;
    } else {
      y += step_y;
      --left_y;
      next_y = left_y > 0 ? crossing(y, step_y, from.y(), d.y()) : kInfinity;
    }
    visit(x, y);
  }
}

void ThrowUnlessValidResolution(double resolution) {
  if (!IsFinitePositive(resolution)) {
    throw Error("occupancy grid: resolution must be a positive number of metres, got " +
                std::to_string(resolution));
  }
}

}  // namespace

OccupancyGrid::OccupancyGrid(double resolution, const Eigen::Vector2d& origin, int width,
                             int height)
    : geometry_(resolution, origin, width, height) {
  if (static_cast<long long>(width) * height > kMaxCells) {
    throw Error("occupancy grid: size " + std::to_string(width) + " x " + std::to_string(height) +
                " is over the limit of " + std::to_string(kMaxCells) + " cells");
  }
  hits_.assign(geometry_.cell_count(), 0);
  misses_.assign(geometry_.cell_count(), 0);
}

namespace {

// The box around every sensor position and beam end point, and the margin around it, with the
// spans and parameters checked as FromScans documents.
struct ScanExtent {
  Eigen::Vector2d lo, hi;
  double margin = 0.0;

  Eigen::Vector2d origin() const { return (lo.array() - margin).matrix(); }
  // Cells along each axis at `resolution`: one more than the extent needs, so that a point
  // exactly on the far edge is inside. In doubles, as a bad extent can be beyond any integer.
  Eigen::Vector2d Cells(double resolution) const {
    return ((hi.array() + margin - origin().array()) / resolution).floor() + 1.0;
  }
};

ScanExtent ExtentOf(std::span<const LaserScan> scans, std::span<const Pose2> poses,
                    double resolution, double margin) {
  if (scans.size() != poses.size()) {
    throw Error("occupancy grid: " + std::to_string(scans.size()) + " scans but " +
                std::to_string(poses.size()) + " poses");
  }
  if (scans.empty()) throw Error("occupancy grid: no scans to build a grid from");
  ThrowUnlessValidResolution(resolution);
  if (!IsFiniteNonNegative(margin)) {
    throw Error("occupancy grid: margin must be a non-negative number of metres");
  }
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(kInfinity);
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-kInfinity);
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const Pose2& pose = poses[i];
    if (!pose.translation().allFinite() || !std::isfinite(pose.theta())) {
      throw Error("occupancy grid: pose " + std::to_string(i) + " is not finite");
    }
    lo = lo.cwiseMin(pose.translation());
    hi = hi.cwiseMax(pose.translation());
    const LaserScan& scan = scans[i];
    for (std::size_t b = 0; b < scan.size(); ++b) {
      if (!scan.is_return(b)) continue;
      const double angle = pose.theta() + scan.angle(b);
      const Eigen::Vector2d end =
          pose.translation() + scan.ranges[b] * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      if (!end.allFinite()) continue;
      lo = lo.cwiseMin(end);
      hi = hi.cwiseMax(end);
    }
  }
  return {lo, hi, margin};
}

}  // namespace

OccupancyGrid OccupancyGrid::FromScans(std::span<const LaserScan> scans,
                                       std::span<const Pose2> poses, double resolution,
                                       double margin) {
  const ScanExtent extent = ExtentOf(scans, poses, resolution, margin);
  const Eigen::Vector2d cells = extent.Cells(resolution);
  if (cells.x() * cells.y() > static_cast<double>(kMaxCells)) {
    const Eigen::Vector2d span = extent.hi - extent.lo;
    std::ostringstream os;
    os << "occupancy grid: the scans span " << span.x() << " x " << span.y() << " m, which at "
       << resolution << " m per cell exceeds " << kMaxCells << " cells; use a coarser resolution";
    throw Error(os.str());
  }
  OccupancyGrid grid(resolution, extent.origin(), static_cast<int>(cells.x()),
                     static_cast<int>(cells.y()));
  for (std::size_t i = 0; i < scans.size(); ++i) grid.InsertScan(scans[i], poses[i]);
  grid.UpdateDistanceField();
  return grid;
}

double OccupancyGrid::FittingResolution(std::span<const LaserScan> scans,
                                        std::span<const Pose2> poses, double resolution,
                                        double margin) {
  const ScanExtent extent = ExtentOf(scans, poses, resolution, margin);
  // Doubling keeps the map's cells aligned with the finer ones; the loop ends, as a finite
  // extent fits in one cell of some finite size.
  while (extent.Cells(resolution).prod() > static_cast<double>(kMaxCells)) resolution *= 2.0;
  return resolution;
}

std::size_t OccupancyGrid::Index(int x, int y) const {
  if (!Contains(x, y)) {
    throw std::out_of_range("occupancy grid: cell (" + std::to_string(x) + ", " +
                            std::to_string(y) + ") outside " + std::to_string(width()) + " x " +
                            std::to_string(height()));
  }
  return geometry_.Index(x, y);
}

double OccupancyGrid::log_odds(int x, int y) const {
  const std::size_t i = Index(x, y);
  return hits_[i] * kHitLogOdds + misses_[i] * kMissLogOdds;
}

double OccupancyGrid::probability(int x, int y) const {
  return 1.0 / (1.0 + std::exp(-log_odds(x, y)));
}

CellState OccupancyGrid::state(int x, int y) const {
  const double l = log_odds(x, y);
  if (l > kOccupiedLogOdds) return CellState::kOccupied;
  if (l < kFreeLogOdds) return CellState::kFree;
  return CellState::kUnknown;
}

bool OccupancyGrid::OccupiedAt(std::size_t index) const {
  return hits_[index] * kHitLogOdds + misses_[index] * kMissLogOdds > kOccupiedLogOdds;
}

void OccupancyGrid::AddHit(std::size_t index) {
  if (hits_[index] != std::numeric_limits<std::uint32_t>::max()) ++hits_[index];
}

void OccupancyGrid::AddMiss(std::size_t index) {
  if (misses_[index] != std::numeric_limits<std::uint32_t>::max()) ++misses_[index];
}

void OccupancyGrid::SetCell(int x, int y, CellState state) {
  const std::size_t i = Index(x, y);
  clearance_.clear();
  hits_[i] = state == CellState::kOccupied ? 1 : 0;
  misses_[i] = 0;
  if (state == CellState::kFree) {
    misses_[i] = static_cast<std::uint32_t>(std::floor(kFreeLogOdds / kMissLogOdds)) + 1;
  }
}

void OccupancyGrid::InsertScan(const LaserScan& scan, const Pose2& pose) {
  if (!pose.translation().allFinite() || !std::isfinite(pose.theta())) {
    throw Error("occupancy grid: cannot insert a scan at a non-finite pose");
  }
  clearance_.clear();
  const Eigen::Vector2d from = geometry_.ToCells(pose.translation());
  struct Beam {
    GridSegment cells;
    bool hit;
  };
  std::vector<Beam> beams;
  beams.reserve(scan.size());
  for (std::size_t b = 0; b < scan.size(); ++b) {
    const float r = scan.ranges[b];
    double length;
    bool hit;
    if (scan.is_return(b)) {
      length = r;
      hit = true;
    } else if (r >= scan.range_max) {  // no return: space is free out to the usable range
      length = std::min(scan.range_max, kNoReturnFreeRange);
      hit = false;
    } else {  // NaN or below range_min: the reading says nothing
      continue;
    }
    const double angle = pose.theta() + scan.angle(b);
    const Eigen::Vector2d to =
        from + (length / resolution()) * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    if (auto cells = ClipToGrid(from, to, width(), height())) {
      beams.push_back({*cells, hit && cells->ends_inside});
    }
  }
  // A beam that grazes a wall crosses cells that neighbouring beams of the same sweep end in;
  // letting those cells gain misses from the same scan would erase walls seen at a slant.
  std::vector<std::size_t> hit_cells;
  for (const Beam& beam : beams) {
    if (beam.hit) hit_cells.push_back(Index(beam.cells.end_x, beam.cells.end_y));
  }
  for (const std::size_t i : hit_cells) AddHit(i);
  std::sort(hit_cells.begin(), hit_cells.end());
  const auto w = static_cast<std::size_t>(width());
  for (const Beam& beam : beams) {
    // ForEachCell stays on the grid, so the index needs no check; a cell without hits cannot be
    // one of this scan's.
    ForEachCell(beam.cells, [&](int x, int y) {
      const std::size_t i = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
      if (hits_[i] == 0 || !std::binary_search(hit_cells.begin(), hit_cells.end(), i)) {
        AddMiss(i);
      }
    });
  }
}

void OccupancyGrid::UpdateDistanceField() {
  const int w = width();
  const int h = height();
  const std::size_t cells = hits_.size();
  std::vector<std::uint8_t> occupied(cells);
  for (std::size_t i = 0; i < cells; ++i) occupied[i] = OccupiedAt(i) ? 1 : 0;
  // A ray heading into the quadrant s = (sx, sy) only visits cells q with (q - c) * s >= 0 on
  // both axes after cell c, so only occupied cells there can stop it. From anywhere in c it may
  // advance by the gap between c's square and the nearest such square: the norm of the
  // per-axis gaps max((q - c) * s - 1, 0). That is the distance from c's centre to the nearest
  // cell of those q grown by one cell back towards c, within the quadrant: a quadrant distance
  // transform of the grown cells, computed here with the quadrant mirrored to up-and-right.
  // The slack keeps leaps short of obstacles despite rounding in the positions along the ray.
  constexpr double kSlack = 1e-3;
  constexpr double kMaxClearance = kOccupiedClearance - 1;
  std::vector<std::uint16_t> clearance(4 * cells);
  std::vector<std::uint8_t> grown(cells);
  std::vector<double> squared(cells);
  for (int quadrant = 0; quadrant < 4; ++quadrant) {
    const bool flip_x = (quadrant & 1) != 0;
    const bool flip_y = (quadrant & 2) != 0;
    const auto mirrored = [&](int a, int b) {
      const int x = flip_x ? w - 1 - a : a;
      const int y = flip_y ? h - 1 - b : b;
      return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
             static_cast<std::size_t>(x);
    };
    for (int b = 0; b < h; ++b) {
      for (int a = 0; a < w; ++a) {
        std::uint8_t g = occupied[mirrored(a, b)];
        if (a + 1 < w) g |= occupied[mirrored(a + 1, b)];
        if (b + 1 < h) g |= occupied[mirrored(a, b + 1)];
        if (a + 1 < w && b + 1 < h) g |= occupied[mirrored(a + 1, b + 1)];
        grown[static_cast<std::size_t>(b) * static_cast<std::size_t>(w) +
              static_cast<std::size_t>(a)] = g;
      }
    }
    SquaredQuadrantDistanceTransform(grown, w, h, squared);
    std::uint16_t* const plane = clearance.data() + quadrant * cells;
    for (int b = 0; b < h; ++b) {
      for (int a = 0; a < w; ++a) {
        const std::size_t i = mirrored(a, b);
        if (occupied[i]) {
          plane[i] = kOccupiedClearance;
          continue;
        }
        const double d = squared[static_cast<std::size_t>(b) * static_cast<std::size_t>(w) +
                                 static_cast<std::size_t>(a)];
        const double c = std::max(0.0, std::sqrt(d) - kSlack);
        plane[i] =
            static_cast<std::uint16_t>(std::min(kMaxClearance, std::floor(c * kClearanceScale)));
      }
    }
  }
  clearance_ = std::move(clearance);
}

double OccupancyGrid::CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const {
  if (!std::isfinite(angle)) return max_range;
  return CastRay(origin, Eigen::Vector2d(std::cos(angle), std::sin(angle)), max_range);
}

double OccupancyGrid::CastRay(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                              double max_range) const {
  if (!(max_range > 0.0) || !origin.allFinite() || !direction.allFinite()) return max_range;
  const double ox = geometry_.CellX(origin.x());
  const double oy = geometry_.CellY(origin.y());
  const double dx = direction.x();
  const double dy = direction.y();
  const double range = max_range / resolution();
  const double t =
      has_distance_field() ? Cast<true>(ox, oy, dx, dy, range) : Cast<false>(ox, oy, dx, dy, range);
  return std::min(max_range, t * resolution());
}

// Everything here is in cells: (ox, oy) is the ray's origin relative to the grid origin, (dx, dy)
// its unit direction. Returns the distance to the first occupied cell, or infinity.
template <bool kUseField>
double OccupancyGrid::Cast(double ox, double oy, double dx, double dy, double max_range) const {
  // An axis the ray runs parallel to is never crossed: its inverse is infinite, its crossing
  // parameter starts out infinite, and so the ray never steps along it.
  const double inv_dx = 1.0 / dx;
  const double inv_dy = 1.0 / dy;
  // Clip the ray to the grid's box, slab by slab.
  double t_enter = 0.0;
  double t_exit = max_range;
  if (dx != 0.0) {
    const double a = (0.0 - ox) * inv_dx;
    const double b = (width() - ox) * inv_dx;
    t_enter = std::max(t_enter, std::min(a, b));
    t_exit = std::min(t_exit, std::max(a, b));
  } else if (ox < 0.0 || ox > width()) {
    return kInfinity;
  }
  if (dy != 0.0) {
    const double a = (0.0 - oy) * inv_dy;
    const double b = (height() - oy) * inv_dy;
    t_enter = std::max(t_enter, std::min(a, b));
    t_exit = std::min(t_exit, std::max(a, b));
  } else if (oy < 0.0 || oy > height()) {
    return kInfinity;
  }
  if (!(t_enter <= t_exit)) return kInfinity;
  // Rays from outside start afresh where they enter, so that every distance below stays small
  // and a leap always moves the ray on, however far away the origin was.
  if (t_enter > 0.0) {
    ox += t_enter * dx;
    oy += t_enter * dy;
    t_exit -= t_enter;
  }

  const int step_x = dx > 0.0 ? 1 : -1;
  const int step_y = dy > 0.0 ? 1 : -1;
  const std::ptrdiff_t stride = width();
  const std::ptrdiff_t step_i_y = step_y * stride;
  const double face_x = dx > 0.0 ? 1.0 : 0.0;  // offset of the face a ray leaves a cell through
  const double face_y = dy > 0.0 ? 1.0 : 0.0;
  // Cells of points on the ray are clamped so that rounding can never leave the grid; for the
  // non-negative values left after clamping, truncation is floor.
  const double last_x = width() - 1;
  const double last_y = height() - 1;
  int x = static_cast<int>(std::clamp(ox, 0.0, last_x));
  int y = static_cast<int>(std::clamp(oy, 0.0, last_y));
  std::ptrdiff_t i = y * stride + x;
  // The clearance plane for this ray's quadrant of directions.
  const std::uint16_t* const field = kUseField
                                         ? clearance_.data() + (dx < 0.0 ? 1 : 0) * hits_.size() +
                                               (dy < 0.0 ? 2 : 0) * hits_.size()
                                         : nullptr;
  // Leaps shorter than a cell cost more than stepping cell by cell; one unsigned comparison
  // also rules out the occupied marker.
  const auto can_leap = [](unsigned clearance) {
    return clearance - kClearanceScale < unsigned{kOccupiedClearance} - kClearanceScale;
  };
  const auto occupied = [&](std::ptrdiff_t index) {
    if constexpr (kUseField) {
      return field[index] == kOccupiedClearance;
    } else {
      return OccupiedAt(static_cast<std::size_t>(index));
    }
  };
  if (occupied(i)) return t_enter;
  double t = 0.0;
  while (true) {
    if constexpr (kUseField) {
      // Leap through free space while the distance field allows it.
      unsigned clearance = field[i];
      if (can_leap(clearance)) {
        do {
          t += clearance * (1.0 / kClearanceScale);
          if (t >= t_exit) return kInfinity;
          x = static_cast<int>(std::clamp(ox + t * dx, 0.0, last_x));
          y = static_cast<int>(std::clamp(oy + t * dy, 0.0, last_y));
          i = y * stride + x;
          clearance = field[i];
        } while (can_leap(clearance));
        if (clearance == kOccupiedClearance) {
          // Landed right on an occupied cell's boundary: report where the ray enters it.
          const double enter_x = dx != 0.0 ? (x + 1.0 - face_x - ox) * inv_dx : -kInfinity;
          const double enter_y = dy != 0.0 ? (y + 1.0 - face_y - oy) * inv_dy : -kInfinity;
          return t_enter + std::max({enter_x, enter_y, 0.0});
        }
      }
    }
    // Step cell by cell (Amanatides-Woo) until an occupied cell or, with the field, room to leap.
    double next_x = dx != 0.0 ? (x + face_x - ox) * inv_dx : kInfinity;
    double next_y = dy != 0.0 ? (y + face_y - oy) * inv_dy : kInfinity;
    while (true) {
      // Written without branches on the axis: which face comes first is a coin toss to the
      // branch predictor.
      const bool along_x = next_x < next_y;
      t = along_x ? next_x : next_y;
      x += along_x ? step_x : 0;
      y += along_x ? 0 : step_y;
      i += along_x ? step_x : step_i_y;
      next_x = along_x ? (x + face_x - ox) * inv_dx : next_x;
      next_y = along_x ? next_y : (y + face_y - oy) * inv_dy;
      if (t >= t_exit || static_cast<unsigned>(x) >= static_cast<unsigned>(width()) ||
          static_cast<unsigned>(y) >= static_cast<unsigned>(height())) {
        return kInfinity;
      }
      if (occupied(i)) return t_enter + t;
      if constexpr (kUseField) {
        if (can_leap(field[i])) break;
      }
    }
  }
}

}  // namespace evoslam
