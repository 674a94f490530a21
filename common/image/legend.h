#ifndef EVOSLAM_COMMON_IMAGE_LEGEND_H_
#define EVOSLAM_COMMON_IMAGE_LEGEND_H_

#include <span>
#include <string>

#include "common/image/image.h"

namespace evoslam {

// How an entry shows what it names: a stroke of a line, a stroke with a dot at each end (a link
// between two places), a filled square (an area's colour, outlined so that white shows), or one
// of a plot's markers (marker.h) as tall as the label's capitals.
enum class LegendMark { kLine, kLink, kSwatch, kDot, kRing, kCross };

struct LegendEntry {
  std::string label;
  Rgb color;
  LegendMark mark = LegendMark::kLine;
  int thickness = 2;  // of a line or link, pixels, as the picture draws it
};

// Pixels the entries take when laid out side by side in rows no wider than `width`, at this text
// scale; 0 for none.
int LegendHeight(std::span<const LegendEntry> entries, int width, int scale);

// Draws the entries, each its mark then its label, side by side from (x, y), starting a new row
// where the next would pass `width`. Labels and outlines are in `ink`.
void DrawLegend(Image& image, int x, int y, int width, std::span<const LegendEntry> entries,
                Rgb ink, int scale);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IMAGE_LEGEND_H_
