#ifndef EVOSLAM_COMMON_IMAGE_MARKER_H_
#define EVOSLAM_COMMON_IMAGE_MARKER_H_

#include "common/image/image.h"

namespace evoslam {

// Shapes that mark a point in a plot or a legend: a filled disc, a ring (to circle a point
// drawn under it) and a diagonal cross (which stands out from a plot's upright grid lines).
enum class Marker { kDot, kRing, kCross };

// Draws the marker centred on pixel coordinates (x, y) and within `radius` pixels of them; a
// ring's and a cross's strokes are wider for larger radii. Non-finite places draw nothing.
void DrawMarker(Image& image, double x, double y, Marker marker, double radius, Rgb color);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_MARKER_H_
