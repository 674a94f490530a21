#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_TRACE_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_TRACE_H_

// The readings a placed scan gives the cells of a grid: one empty reading for every cell a beam
// crosses before its return, one occupied reading for the cell it ends in (a beam cut to the
// maximum range gives empty readings to every cell it crosses, the last one too). The grid and its
// overlays both trace scans through this one function, so that the same scan at the same pose
// gives the same readings to the bit, whoever asks.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "common/grid/grid_geometry.h"
#include "common/slam/immune/evidence_model.h"
#include "common/slam/immune/evidence_scan.h"

namespace evoslam::evidence_trace {

// Clips the beam from `o` along `d` for [t0, t1] to the closed interval [0, size] of one axis.
inline void ClipAxis(double o, double d, double size, double& t0, double& t1) {
  if (d == 0.0) {
    if (!(o >= 0.0 && o <= size)) t1 = -1.0;  // runs outside the grid: nothing of it is in
    return;
  }
  const double inverse = 1.0 / d;
  const double a = -o * inverse;
  const double b = (size - o) * inverse;
  t0 = std::max(t0, std::min(a, b));
  t1 = std::min(t1, std::max(a, b));
}

inline int ClampCell(double v, int n) {
  return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1)));
}

// How a visitor numbers the cells: cell (x, y) of the grid is (y - y0) * stride + (x - x0), so that
// an overlay can keep its changes for just the part of the grid its scans reach.
struct CellNumbering {
  int x0 = 0;
  int y0 = 0;
  std::ptrdiff_t stride = 0;
};

// Traces one beam from `o` (in cells) along the unit direction `d` for `length` cells, the part in
// the grid only. Amanatides and Woo's walk from cell to cell; counting the steps left on each axis
// makes it end on the end cell whatever the rounding of the crossings. A cell's empty reading is
// weighed at the middle of the stretch of beam inside it. The walk keeps its branch on which axis
// comes next: written without it, the walk measured a fifth slower (docs/benchmarks.md).
template <typename Visitor>
void TraceBeam(const GridGeometry& grid, const EmptyWeights& weights,
               const CellNumbering& numbering, double ox, double oy, double dx, double dy,
               double length, std::uint32_t occupied_units, Visitor& visitor) {
  const int w = grid.width();
  const int h = grid.height();
  const EmptyWeights::View empty_units(weights);
  double t0 = 0.0;
  double t1 = length;
  ClipAxis(ox, dx, w, t0, t1);
  ClipAxis(oy, dy, h, t0, t1);
  if (!(t0 <= t1)) return;
  int x = ClampCell(ox + t0 * dx, w);
  int y = ClampCell(oy + t0 * dy, h);
  const double end_x = std::floor(ox + t1 * dx);
  const double end_y = std::floor(oy + t1 * dy);
  // The return's cell only when the return itself lies in the grid.
  const bool hit =
      occupied_units > 0 && t1 == length && end_x >= 0.0 && end_x < w && end_y >= 0.0 && end_y < h;
  const int last_x = ClampCell(end_x, w);
  const int last_y = ClampCell(end_y, h);
  int left_x = std::abs(last_x - x);
  int left_y = std::abs(last_y - y);
  const int step_x = last_x >= x ? 1 : -1;
  const std::ptrdiff_t step_row = last_y >= y ? numbering.stride : -numbering.stride;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  const double every_x = left_x > 0 ? std::abs(1.0 / dx) : kNever;
  const double every_y = left_y > 0 ? std::abs(1.0 / dy) : kNever;
  double next_x = left_x > 0 ? (x + (step_x > 0) - ox) / dx : kNever;
  double next_y = left_y > 0 ? (y + (step_row > 0) - oy) / dy : kNever;
  std::ptrdiff_t cell = (y - numbering.y0) * numbering.stride + (x - numbering.x0);
  double t_in = t0;
  for (int n = left_x + left_y; n > 0; --n) {
    const bool along_x = next_x < next_y;
    const double t_out = along_x ? next_x : next_y;
    visitor.Empty(static_cast<std::size_t>(cell), empty_units.at(0.5 * (t_in + t_out)));
    t_in = t_out;
    if (along_x) {
      cell += step_x;
      next_x = --left_x > 0 ? next_x + every_x : kNever;
    } else {
      cell += step_row;
      next_y = --left_y > 0 ? next_y + every_y : kNever;
    }
  }
  if (hit) {
    visitor.Occupied(static_cast<std::size_t>(cell), occupied_units);
  } else {
    visitor.Empty(static_cast<std::size_t>(cell), empty_units.at(0.5 * (t_in + t1)));
  }
}

// Traces every beam of a placed scan. A pose that is not finite puts the scan nowhere: it gives
// nothing, as points outside the grid give nothing.
template <typename Visitor>
void TraceScan(const GridGeometry& grid, const EmptyWeights& weights,
               const CellNumbering& numbering, const PlacedScan& placed, Visitor& visitor) {
  const Pose2& pose = placed.pose;
  if (!std::isfinite(pose.x()) || !std::isfinite(pose.y()) || !std::isfinite(pose.theta())) {
    return;
  }
  const double c = std::cos(pose.theta());
  const double s = std::sin(pose.theta());
  const double ox = grid.CellX(pose.x());
  const double oy = grid.CellY(pose.y());
  const double cells_per_m = 1.0 / grid.resolution();
  for (const EvidenceBeam& beam : placed.scan->beams()) {
    TraceBeam(grid, weights, numbering, ox, oy, c * beam.x - s * beam.y, s * beam.x + c * beam.y,
              beam.range_m * cells_per_m, beam.occupied_units, visitor);
  }
}

}  // namespace evoslam::evidence_trace

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_TRACE_H_
