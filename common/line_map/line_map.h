#ifndef EVOSLAM_COMMON_LINE_MAP_LINE_MAP_H_
#define EVOSLAM_COMMON_LINE_MAP_LINE_MAP_H_

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace evoslam {

// A wall: the straight segment from a to b, metres, world frame.
struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
};

struct Bounds {
  Eigen::Vector2d min{0.0, 0.0};
  Eigen::Vector2d max{0.0, 0.0};
};

// A map of walls as line segments, with a uniform-grid index so that a ray cast or a
// neighbourhood query visits only the walls near the ray or the query, however many walls the
// map holds.
class LineMap {
 public:
  LineMap() = default;
  // cell_size: edge of the index's grid cells, metres.
  explicit LineMap(std::vector<Segment> segments, double cell_size = 0.5);

  std::span<const Segment> segments() const { return segments_; }
  std::size_t size() const { return segments_.size(); }
  bool empty() const { return segments_.empty(); }
  const Bounds& bounds() const { return bounds_; }

  // Distance from origin along the ray at `angle` (radians, world frame) to the first wall, or
  // max_range when no wall lies within max_range.
  double CastRay(const Eigen::Vector2d& origin, double angle, double max_range) const;
  // The same along a unit direction, for callers that keep directions and so skip the sine and
  // cosine.
  double CastRay(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                 double max_range) const;

  // Indices (ascending) of the walls that come within `radius` of `center`.
  std::vector<std::size_t> SegmentsNear(const Eigen::Vector2d& center, double radius) const;

 private:
  // Implementation-defined index members live here.
  std::vector<Segment> segments_;
  Bounds bounds_;
  double cell_size_ = 0.5;
  Eigen::Vector2d grid_origin_{0.0, 0.0};
  int cols_ = 0;
  int rows_ = 0;
  std::vector<std::uint32_t> cell_start_;  // CSR offsets, size cols_*rows_+1
  std::vector<std::uint32_t> cell_items_;  // segment indices per cell

  // Each cell entry's wall as start point and direction (b - a), stored beside cell_items_ so
  // that a ray's inner loop reads one contiguous run of memory per cell.
  struct CellWall {
    double ax;
    double ay;
    double ex;
    double ey;
  };
  std::vector<CellWall> cell_walls_;
  double inv_cell_size_ = 2.0;
};

// Text format: one wall per line, "x1 y1 x2 y2" in metres; '#' starts a comment; blank lines
// are ignored. Plain, gzip or bzip2, as LineReader reads. Errors name the file and line.
LineMap ReadLineMap(const std::filesystem::path& path);
void WriteLineMap(const LineMap& map, const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LINE_MAP_LINE_MAP_H_
