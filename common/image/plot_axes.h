#ifndef EVOSLAM_COMMON_IMAGE_PLOT_AXES_H_
#define EVOSLAM_COMMON_IMAGE_PLOT_AXES_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/image/image.h"

namespace evoslam {

// One axis of a plot: the values it spans, its name, and whether its ticks fall on whole numbers
// only (an axis of indices or counts).
struct PlotAxis {
  double min = 0.0;
  double max = 1.0;
  std::string label;
  bool whole = false;
};

// An axis spanning the values from lo to hi widened by `fraction` of that span on each side, so
// that marks at the extremes stay clear of the frame; lo == hi gets a span of a tenth of its size
// (1 for zero) around it. Throws Error for non-finite values, lo > hi, a negative fraction, or a
// span a double cannot hold.
PlotAxis PaddedAxis(double lo, double hi, double fraction, std::string label, bool whole = false);

// Where an axis's ticks go and what they say.
struct PlotTicks {
  double step = 0.0;
  std::vector<double> values;
  std::vector<std::string> texts;  // each value with the digits the step needs
};

// Round values for the axis's ticks: the multiples within [min, max] of the smallest step of 1, 2
// or 5 times a power of ten (at least 1 on a whole axis) of which there are at most max_ticks.
// Numbers are written with the decimals the step needs ("0.95" for a step of 0.05, "1200" for
// 100), or in exponent form when the largest is a million or more or the step needs more than 8
// decimals. Throws Error for an axis whose min is not finite and below its max, or max_ticks < 1.
PlotTicks MakePlotTicks(const PlotAxis& axis, int max_ticks);

// A plot's frame in an image: the axes' values mapped onto a rectangle of pixels, the plot area,
// with room around it for the ticks' numbers and the axes' names. Larger values lie right and up.
class PlotAxes {
 public:
  // Lays the plot out in the `size` pixels whose top-left pixel is `top_left`: the y axis's name
  // over the plot area's top-left corner, the x axis's under the ticks' numbers, as many ticks as
  // there is room for their numbers. Throws Error for an axis MakePlotTicks refuses, or a box too
  // small to leave a plot area of 20 x 20 pixels or a text scale below 1.
  PlotAxes(const Eigen::Vector2i& top_left, const Eigen::Vector2i& size, PlotAxis x, PlotAxis y,
           int text_scale);

  const PlotAxis& x() const { return x_; }
  const PlotAxis& y() const { return y_; }
  const PlotTicks& x_ticks() const { return x_ticks_; }
  const PlotTicks& y_ticks() const { return y_ticks_; }
  // The plot area's top-left pixel and size; the axes' min and max lie on its outermost pixels'
  // centres, and the frame is drawn a pixel outside it.
  const Eigen::Vector2i& area_top_left() const { return area_top_left_; }
  const Eigen::Vector2i& area_size() const { return area_size_; }

  // Continuous pixel coordinates of a value (pixel centres at integers).
  Eigen::Vector2d ToPixel(const Eigen::Vector2d& value) const;

  // Draws grid lines at the ticks in `grid`; the frame, the ticks, their numbers and the axes'
  // names in `ink`. What the plot shows is drawn after, over the grid lines.
  void Draw(Image& image, Rgb ink, Rgb grid) const;

 private:
  PlotAxis x_;
  PlotAxis y_;
  int text_scale_;
  PlotTicks x_ticks_;
  PlotTicks y_ticks_;
  Eigen::Vector2i top_left_;
  Eigen::Vector2i area_top_left_;
  Eigen::Vector2i area_size_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_PLOT_AXES_H_
