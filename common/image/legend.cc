#include "common/image/legend.h"

#include <Eigen/Core>
#include <vector>

#include "common/image/bitmap_font.h"
#include "common/image/marker.h"

namespace evoslam {
namespace {

// In font pixels: a mark's length, the gap between a mark and its label, between entries, and
// the pitch of rows.
constexpr int kMarkLength = 16;
constexpr int kMarkGap = 4;
constexpr int kEntryGap = 12;
constexpr int kRowPitch = 14;

int EntryWidth(const LegendEntry& entry, int scale) {
  return (kMarkLength + kMarkGap) * scale + TextWidth(entry.label, scale);
}

// Each entry's top-left corner relative to the legend's.
std::vector<Eigen::Vector2i> LayOut(std::span<const LegendEntry> entries, int width, int scale) {
  std::vector<Eigen::Vector2i> places;
  Eigen::Vector2i at(0, 0);
  for (const LegendEntry& entry : entries) {
    if (at.x() > 0 && at.x() + EntryWidth(entry, scale) > width)
      at = {0, at.y() + kRowPitch * scale};
    places.push_back(at);
    at.x() += EntryWidth(entry, scale) + kEntryGap * scale;
  }
  return places;
}

Marker MarkerOf(LegendMark mark) {
  if (mark == LegendMark::kRing) return Marker::kRing;
  return mark == LegendMark::kCross ? Marker::kCross : Marker::kDot;
}

void DrawMark(Image& image, int x, int y, const LegendEntry& entry, Rgb ink, int scale) {
  const int length = kMarkLength * scale;
  const double middle = y + (kCapitalHeight * scale - 1) / 2.0;
  switch (entry.mark) {
    case LegendMark::kLine:
      image.DrawLine(x, middle, x + length - 1, middle, entry.color, entry.thickness);
      break;
    case LegendMark::kLink: {
      const double radius = 2.0 * scale;
      image.DrawLine(x + radius, middle, x + length - 1 - radius, middle, entry.color,
                     entry.thickness);
      image.DrawDisc(x + radius, middle, radius, entry.color);
      image.DrawDisc(x + length - 1 - radius, middle, radius, entry.color);
      break;
    }
    case LegendMark::kSwatch: {
      const int side = kCapitalHeight * scale;
      const int left = x + (length - side) / 2;
      image.FillRect(left, y, side, side, ink);
      image.FillRect(left + 1, y + 1, side - 2, side - 2, entry.color);
      break;
    }
    case LegendMark::kDot:
    case LegendMark::kRing:
    case LegendMark::kCross:
      DrawMarker(image, x + (length - 1) / 2.0, middle, MarkerOf(entry.mark),
                 kCapitalHeight * scale / 2.0, entry.color);
      break;
  }
}

}  // namespace

int LegendHeight(std::span<const LegendEntry> entries, int width, int scale) {
  if (entries.empty()) return 0;
  return LayOut(entries, width, scale).back().y() + TextHeight(scale);
}

void DrawLegend(Image& image, int x, int y, int width, std::span<const LegendEntry> entries,
                Rgb ink, int scale) {
  const std::vector<Eigen::Vector2i> places = LayOut(entries, width, scale);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int left = x + places[i].x();
    const int top = y + places[i].y();
    DrawMark(image, left, top, entries[i], ink, scale);
    DrawText(image, left + (kMarkLength + kMarkGap) * scale, top, entries[i].label, ink, scale);
  }
}

}  // namespace evoslam
