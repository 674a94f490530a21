#ifndef EVOSLAM_COMMON_GRID_DISTANCE_TRANSFORM_H_
#define EVOSLAM_COMMON_GRID_DISTANCE_TRANSFORM_H_

#include <cstdint>
#include <span>

namespace evoslam {

// Squared Euclidean distance, in cells, from each cell (x, y) of a width x height raster
// (row-major, row y at y * width) to the nearest seed (non-zero entry) (sx, sy) with sx >= x and
// sy >= y: the only cells a ray heading up and to the right (in raster coordinates) can reach from
// (x, y). Infinity when there is none. Written to `out`, of width * height entries, so that repeated
// calls can share one buffer. Lower envelope of parabolas (Felzenszwalb and Huttenlocher), one-sided;
// O(width * height * log(width)).
void SquaredQuadrantDistanceTransform(std::span<const std::uint8_t> seeds, int width, int height,
                                      std::span<double> out);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_GRID_DISTANCE_TRANSFORM_H_
