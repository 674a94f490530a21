#include "common/slam/immune/scan_gaps.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <optional>
#include <span>

namespace evoslam {
namespace {

// What one beam says of the surface along it.
enum class GapBeamKind {
  kSurface,  // a return within reach
  kBeyond,   // nothing within reach: stands for a point at the reach
  kUnknown,  // nothing can be told
};

struct GapBeam {
  GapBeamKind kind = GapBeamKind::kUnknown;
  double range = 0.0;  // of `point`
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
};

// Beams [first, last], successive points that eq. 6 joins.
struct GapSection {
  std::size_t first = 0;
  std::size_t last = 0;
  bool kept = false;
};

std::vector<GapBeam> ClassifyGapBeams(const LaserScan& scan, double max_range_m) {
  const double reach = std::min(max_range_m, scan.range_max);
  std::vector<GapBeam> beams(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double r = scan.ranges[i];
    GapBeam& beam = beams[i];
    if (scan.is_return(i) && r < reach) {
      beam.kind = GapBeamKind::kSurface;
      beam.range = r;
    } else if (scan.is_return(i) || r >= scan.range_max) {
      beam.kind = GapBeamKind::kBeyond;
      beam.range = reach;
    } else {
      continue;  // NaN, or at or below range_min
    }
    const double a = scan.angle(i);
    beam.point = beam.range * Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  return beams;
}

// Eq. 6 without the division, so that it holds for no pair of points at range zero.
bool SameGapSection(const GapBeam& a, const GapBeam& b, double section_ratio) {
  return (a.point - b.point).norm() < section_ratio * std::min(a.range, b.range);
}

std::vector<GapSection> CutGapSections(std::span<const GapBeam> beams,
                                       const proto::KeyPointParams& params) {
  std::vector<GapSection> sections;
  bool open = false;
  for (std::size_t i = 0; i < beams.size(); ++i) {
    if (beams[i].kind == GapBeamKind::kUnknown) {
      open = false;
    } else if (open && SameGapSection(beams[i - 1], beams[i], params.section_ratio())) {
      sections.back().last = i;
    } else {
      sections.push_back({i, i, false});
      open = true;
    }
  }
  for (GapSection& s : sections) s.kept = s.last - s.first + 1 >= params.min_section_points();
  return sections;
}

// The gap at the end of kept section `k` that faces `step` (-1: its first beam, +1: its last).
std::optional<ScanGap> GapAtSectionEnd(std::span<const GapBeam> beams,
                                       std::span<const GapSection> sections, std::ptrdiff_t k,
                                       std::ptrdiff_t step, double min_gap_m) {
  const auto beam_count = static_cast<std::ptrdiff_t>(beams.size());
  const auto section_count = static_cast<std::ptrdiff_t>(sections.size());
  const auto edge = static_cast<std::ptrdiff_t>(step > 0 ? sections[k].last : sections[k].first);
  const std::ptrdiff_t beyond = edge + step;
  if (beams[edge].kind != GapBeamKind::kSurface || beyond < 0 || beyond == beam_count) {
    return std::nullopt;
  }
  // The section must end at a step away from the sensor, not where something nearer hides it.
  if (beams[beyond].kind == GapBeamKind::kUnknown || !(beams[beyond].range > beams[edge].range)) {
    return std::nullopt;
  }
  // Across dropped sections to the next kept one; an unknown reading between leaves the far
  // side unseen.
  for (std::ptrdiff_t j = k, next = k + step; next >= 0 && next < section_count;
       j = next, next += step) {
    const GapSection& near = sections[j];
    const GapSection& far = sections[next];
    const bool adjacent = step > 0 ? far.first == near.last + 1 : far.last + 1 == near.first;
    if (!adjacent) return std::nullopt;
    if (!far.kept) continue;
    const std::size_t facing = step > 0 ? far.first : far.last;
    const double width = (beams[facing].point - beams[edge].point).norm();
    if (!(width > min_gap_m)) return std::nullopt;
    return ScanGap{static_cast<std::size_t>(edge), beams[edge].point, width};
  }
  return std::nullopt;
}

}  // namespace

std::vector<ScanGap> FindScanGaps(const LaserScan& scan, const proto::KeyPointParams& params,
                                  double max_range_m) {
  const std::vector<GapBeam> beams = ClassifyGapBeams(scan, max_range_m);
  const std::vector<GapSection> sections = CutGapSections(beams, params);
  std::vector<ScanGap> gaps;
  for (std::ptrdiff_t k = 0; k < std::ssize(sections); ++k) {
    if (!sections[k].kept) continue;
    for (const std::ptrdiff_t step : {-1, +1}) {
      if (auto gap = GapAtSectionEnd(beams, sections, k, step, params.min_gap_m())) {
        gaps.push_back(*gap);
      }
    }
  }
  return gaps;
}

}  // namespace evoslam
