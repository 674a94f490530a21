#ifndef EVOSLAM_COMMON_LOCALIZATION_SEGMENT_RENDERER_H_
#define EVOSLAM_COMMON_LOCALIZATION_SEGMENT_RENDERER_H_

#include <span>
#include <vector>

#include "common/line_map/line_map.h"
#include "common/localization/range_renderer.h"

namespace evoslam {

// Renders a small set of walls (the temporary map around the robot) by sweeping each wall over
// the fan's angular bins, keeping the nearest hit per ray: the cost is the number of walls plus
// the number of (ray, wall) crossings, instead of rays times walls.
class SegmentRenderer : public RangeRenderer {
 public:
  explicit SegmentRenderer(std::span<const Segment> walls);

  void Render(const Eigen::Vector2d& origin, const RayFan& fan, float max_range,
              std::span<float> ranges) const override;

  std::size_t size() const { return ax_.size(); }

 private:
  // Structure of arrays: the sweep reads each wall's coordinates once per render.
  std::vector<double> ax_, ay_, bx_, by_;
};

// The temporary map: the walls of `map` within `radius` of `center`, the only ones a laser in the
// search window can see.
std::vector<Segment> TemporaryMap(const LineMap& map, const Eigen::Vector2d& center, double radius);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_LOCALIZATION_SEGMENT_RENDERER_H_
