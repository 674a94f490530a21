#include "common/line_map/line_map.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "common/io/line_reader.h"
#include "common/io/text_fields.h"
#include "common/line_map/segment_geometry.h"
#include "common/util/error.h"
#include "common/util/finite_checks.h"
#include "common/util/infinity.h"

namespace evoslam {
namespace {

// A map spanning kilometres at a fine cell size would need more memory than it is worth; beyond
// this many cells the index coarsens its cells instead.
constexpr double kMaxCells = 4.0 * 1024 * 1024;

// Walls are registered in every cell they come within this distance of (relative to the cell
// size), so that a hit exactly on a cell border is found from either side despite rounding.
constexpr double kRegistrationSlack = 1e-6;

// Rays within this angle (radians) of a wall's direction are taken as parallel to it.
constexpr double kParallel = 1e-12;

// Liang-Barsky: does the closed segment a + u (b - a), u in [0, 1], meet the closed box?
bool SegmentMeetsBox(const Segment& s, double x0, double y0, double x1, double y1) {
  double u0 = 0.0;
  double u1 = 1.0;
  const double d[2] = {s.b.x() - s.a.x(), s.b.y() - s.a.y()};
  const double start[2] = {s.a.x(), s.a.y()};
  const double lo[2] = {x0, y0};
  const double hi[2] = {x1, y1};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (start[k] < lo[k] || start[k] > hi[k]) return false;
      continue;
    }
    double ua = (lo[k] - start[k]) / d[k];
    double ub = (hi[k] - start[k]) / d[k];
    if (ua > ub) std::swap(ua, ub);
    u0 = std::max(u0, ua);
    u1 = std::min(u1, ub);
    if (u0 > u1) return false;
  }
  return true;
}

int CellIndex(double coordinate, double origin, double inv_cell_size, int count) {
  const double cell = std::floor((coordinate - origin) * inv_cell_size);
  if (!(cell > 0.0)) return 0;  // also maps NaN to 0
  if (cell >= count - 1) return count - 1;
  return static_cast<int>(cell);
}

}  // namespace

LineMap::LineMap(std::vector<Segment> segments, double cell_size)
    : segments_(std::move(segments)), cell_size_(cell_size) {
  if (!IsFinitePositive(cell_size)) {
    throw Error("line map: cell size must be a positive number, got " + FormatShortest(cell_size));
  }
  if (segments_.size() >= std::numeric_limits<std::uint32_t>::max()) {
    throw Error("line map: too many walls (" + std::to_string(segments_.size()) + ")");
  }
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    if (!s.a.allFinite() || !s.b.allFinite()) {
      throw Error("line map: wall " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  if (segments_.empty()) return;

  bounds_.min = segments_.front().a;
  bounds_.max = segments_.front().a;
  for (const Segment& s : segments_) {
    bounds_.min = bounds_.min.cwiseMin(s.a).cwiseMin(s.b);
    bounds_.max = bounds_.max.cwiseMax(s.a).cwiseMax(s.b);
  }
  const Eigen::Vector2d extent = bounds_.max - bounds_.min;
  const auto cells_for = [&extent](double size) {
    return (std::floor(extent.x() / size) + 1.0) * (std::floor(extent.y() / size) + 1.0);
  };
  while (cells_for(cell_size_) > kMaxCells) cell_size_ *= 1.5;
  inv_cell_size_ = 1.0 / cell_size_;
  // The grid reaches a little beyond the walls so that a ray running along the outermost wall
  // line, off it only by rounding, still finds the walls that end there.
  const double slack = kRegistrationSlack * cell_size_;
  grid_origin_ = bounds_.min.array() - slack;
  cols_ = static_cast<int>(std::floor((extent.x() + 2 * slack) * inv_cell_size_)) + 1;
  rows_ = static_cast<int>(std::floor((extent.y() + 2 * slack) * inv_cell_size_)) + 1;

  // Calls visit(cell) for every cell the wall passes through (or grazes within the slack).
  const auto for_each_cell = [&](const Segment& s, auto&& visit) {
    const Eigen::Vector2d lo = s.a.cwiseMin(s.b);
    const Eigen::Vector2d hi = s.a.cwiseMax(s.b);
    const int ix0 = CellIndex(lo.x() - slack, grid_origin_.x(), inv_cell_size_, cols_);
    const int ix1 = CellIndex(hi.x() + slack, grid_origin_.x(), inv_cell_size_, cols_);
    const int iy0 = CellIndex(lo.y() - slack, grid_origin_.y(), inv_cell_size_, rows_);
    const int iy1 = CellIndex(hi.y() + slack, grid_origin_.y(), inv_cell_size_, rows_);
    for (int iy = iy0; iy <= iy1; ++iy) {
      const double y0 = grid_origin_.y() + iy * cell_size_;
      for (int ix = ix0; ix <= ix1; ++ix) {
        const double x0 = grid_origin_.x() + ix * cell_size_;
        if (SegmentMeetsBox(s, x0 - slack, y0 - slack, x0 + cell_size_ + slack,
                            y0 + cell_size_ + slack)) {
          visit(static_cast<std::size_t>(iy) * cols_ + ix);
        }
      }
    }
  };

  const std::size_t cell_count = static_cast<std::size_t>(cols_) * rows_;
  cell_start_.assign(cell_count + 1, 0);
  for (const Segment& s : segments_) {
    for_each_cell(s, [this](std::size_t cell) { ++cell_start_[cell + 1]; });
  }
  for (std::size_t c = 0; c < cell_count; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(cell_start_.back());
  cell_walls_.resize(cell_start_.back());
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& s = segments_[i];
    const CellWall wall{s.a.x(), s.a.y(), s.b.x() - s.a.x(), s.b.y() - s.a.y()};
    for_each_cell(s, [&](std::size_t cell) {
      cell_items_[fill[cell]] = static_cast<std::uint32_t>(i);
      cell_walls_[fill[cell]] = wall;
      ++fill[cell];
    });
  }
}

double LineMap::CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const {
  return CastRay(origin, Eigen::Vector2d(std::cos(angle), std::sin(angle)), max_range);
}

double LineMap::CastRay(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                        double max_range) const {
  if (segments_.empty() || !(max_range > 0.0)) return max_range;
  const double dx = direction.x();
  const double dy = direction.y();
  const double ox = origin.x();
  const double oy = origin.y();
  const double gx0 = grid_origin_.x();
  const double gy0 = grid_origin_.y();
  const double gx1 = gx0 + cols_ * cell_size_;
  const double gy1 = gy0 + rows_ * cell_size_;

  // A ray from outside is clipped to the grid and starts in the cell where it enters; from
  // inside, the walk ends when it leaves the grid.
  double t_enter = 0.0;
  if (!(ox >= gx0 && ox <= gx1 && oy >= gy0 && oy <= gy1)) {
    double t_exit = max_range;
    const auto clip = [&t_enter, &t_exit](double o, double d, double lo, double hi) {
      if (d == 0.0) return o >= lo && o <= hi;
      double ta = (lo - o) / d;
      double tb = (hi - o) / d;
      if (ta > tb) std::swap(ta, tb);
      t_enter = std::max(t_enter, ta);
      t_exit = std::min(t_exit, tb);
      return t_enter <= t_exit;
    };
    if (!clip(ox, dx, gx0, gx1) || !clip(oy, dy, gy0, gy1)) return max_range;
  }

  int ix = CellIndex(ox + t_enter * dx, gx0, inv_cell_size_, cols_);
  int iy = CellIndex(oy + t_enter * dy, gy0, inv_cell_size_, rows_);
  const int step_x = dx > 0.0 ? 1 : -1;
  const int step_y = dy > 0.0 ? 1 : -1;
  const double t_delta_x = dx != 0.0 ? cell_size_ / std::abs(dx) : kInfinity;
  const double t_delta_y = dy != 0.0 ? cell_size_ / std::abs(dy) : kInfinity;
  double t_max_x = dx > 0.0   ? (gx0 + (ix + 1) * cell_size_ - ox) / dx
                   : dx < 0.0 ? (gx0 + ix * cell_size_ - ox) / dx
                              : kInfinity;
  double t_max_y = dy > 0.0   ? (gy0 + (iy + 1) * cell_size_ - oy) / dy
                   : dy < 0.0 ? (gy0 + iy * cell_size_ - oy) / dy
                              : kInfinity;

  const CellWall* const walls = cell_walls_.data();
  const std::uint32_t* const starts = cell_start_.data();
  double best = max_range;
  for (;;) {
    const std::size_t cell = static_cast<std::size_t>(iy) * cols_ + ix;
    const CellWall* const end = walls + starts[cell + 1];
    for (const CellWall* w = walls + starts[cell]; w != end; ++w) {
      // Ray o + t d meets wall a + s e at t = (w x e) / (d x e), s = (w x d) / (d x e), with
      // w = a - o; the tests below are those with the denominator made positive, so that the
      // only division is for a hit nearer than the best so far.
      double den = dx * w->ey - dy * w->ex;
      const double wx = w->ax - ox;
      const double wy = w->ay - oy;
      double t_num = wx * w->ey - wy * w->ex;
      double s_num = wx * dy - wy * dx;
      if (den < 0.0) {
        den = -den;
        t_num = -t_num;
        s_num = -s_num;
      }
      // Parallel to rounding: a grazing ray does not count as a hit.
      const bool crossing = den > kParallel * (std::abs(w->ex) + std::abs(w->ey));
      if (crossing && t_num >= 0.0 && s_num >= 0.0 && s_num <= den && t_num < best * den) {
        best = t_num / den;
      }
    }
    // Walls not yet tested can only be met in cells further along the ray.
    const double t_next = std::min(t_max_x, t_max_y);
    if (best <= t_next) break;
    if (t_max_x < t_max_y) {
      ix += step_x;
      if (ix < 0 || ix >= cols_) break;
      t_max_x += t_delta_x;
    } else {
      iy += step_y;
      if (iy < 0 || iy >= rows_) break;
      t_max_y += t_delta_y;
    }
  }
  return std::min(best, max_range);
}

std::vector<std::size_t> LineMap::SegmentsNear(const Eigen::Vector2d& center, double radius) const {
  std::vector<std::size_t> result;
  if (segments_.empty() || !(radius >= 0.0) || !center.allFinite()) return result;
  const double gx1 = grid_origin_.x() + cols_ * cell_size_;
  const double gy1 = grid_origin_.y() + rows_ * cell_size_;
  if (center.x() + radius < grid_origin_.x() || center.x() - radius > gx1 ||
      center.y() + radius < grid_origin_.y() || center.y() - radius > gy1) {
    return result;
  }
  const int ix0 = CellIndex(center.x() - radius, grid_origin_.x(), inv_cell_size_, cols_);
  const int ix1 = CellIndex(center.x() + radius, grid_origin_.x(), inv_cell_size_, cols_);
  const int iy0 = CellIndex(center.y() - radius, grid_origin_.y(), inv_cell_size_, rows_);
  const int iy1 = CellIndex(center.y() + radius, grid_origin_.y(), inv_cell_size_, rows_);
  for (int iy = iy0; iy <= iy1; ++iy) {
    for (int ix = ix0; ix <= ix1; ++ix) {
      const std::size_t cell = static_cast<std::size_t>(iy) * cols_ + ix;
      for (std::uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
        result.push_back(cell_items_[k]);
      }
    }
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  std::erase_if(result,
                [&](std::size_t i) { return PointSegmentDistance(center, segments_[i]) > radius; });
  return result;
}

LineMap ReadLineMap(const std::filesystem::path& path) {
  LineReader in(path);
  const std::string& source = in.source();
  std::vector<Segment> segments;
  std::vector<std::string_view> fields;
  while (const std::optional<std::string_view> line = in.Next()) {
    const std::size_t line_number = in.line_number();
    SplitFields(StripHashComment(*line), &fields);
    if (fields.empty()) continue;
    if (fields.size() != 4) {
      throw InputError(source, line_number,
                       "expected a wall as 4 numbers \"x1 y1 x2 y2\", found " +
                           std::to_string(fields.size()) + " fields");
    }
    double v[4];
    for (int k = 0; k < 4; ++k) {
      const std::optional<double> value = ParseDouble(fields[k]);
      if (!value || !std::isfinite(*value)) {
        throw InputError(source, line_number,
                         "expected a finite number for field " + std::to_string(k + 1) +
                             " of \"x1 y1 x2 y2\", found \"" + std::string(fields[k]) + "\"");
      }
      v[k] = *value;
    }
    Segment s{{v[0], v[1]}, {v[2], v[3]}};
    if (s.a == s.b) {
      throw InputError(source, line_number, "expected a wall of non-zero length, both ends equal");
    }
    segments.push_back(s);
  }
  return LineMap(std::move(segments));
}

void WriteLineMap(const LineMap& map, const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw Error(path.string() + ": cannot open line map for writing");
  out << "# evoslam line map: one wall per line, x1 y1 x2 y2 in metres\n";
  for (const Segment& s : map.segments()) {
    out << FormatShortest(s.a.x()) << ' ' << FormatShortest(s.a.y()) << ' '
        << FormatShortest(s.b.x()) << ' ' << FormatShortest(s.b.y()) << '\n';
  }
  out.close();
  if (!out) throw Error(path.string() + ": error while writing line map");
}

}  // namespace evoslam
