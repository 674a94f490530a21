#ifndef EVOSLAM_COMMON_IMAGE_SCALE_BAR_H_
#define EVOSLAM_COMMON_IMAGE_SCALE_BAR_H_

#include <Eigen/Core>
#include <string>

#include "common/image/image.h"

namespace evoslam {

// A bar of a round length in metres, for reading distances off a picture.
struct ScaleBar {
  double metres = 0.0;
  int pixels = 0;
  std::string label;  // "5 m"
};

// The longest bar of 1, 2 or 5 times a power of ten metres that spans at most `max_pixels`.
// Throws Error unless metres_per_pixel is finite and positive and max_pixels positive.
ScaleBar MakeScaleBar(double metres_per_pixel, int max_pixels);

// Width and height of the bar as DrawScaleBar draws it, label included, at this text scale.
Eigen::Vector2i ScaleBarSize(const ScaleBar& bar, int scale);

// Draws the label centred over the bar, and the bar, with ticks up at its ends, as a run of
// exactly bar.pixels pixels; (x, y) is the top-left corner of ScaleBarSize.
void DrawScaleBar(Image& image, int x, int y, const ScaleBar& bar, Rgb color, int scale);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_SCALE_BAR_H_
