#include "common/line_map/line_map_svg.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <string>
#include <string_view>

#include "common/util/error.h"
#include "common/util/finite_checks.h"

namespace evoslam {
namespace {

constexpr std::array<std::string_view, 6> kPalette = {"#d62728", "#1f77b4", "#2ca02c",
                                                      "#ff7f0e", "#9467bd", "#8c564b"};
constexpr double kMarginMetres = 0.5;

std::string Number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.3f", value);
  return buffer;
}

}  // namespace

void WriteSvg(const LineMap& map, const std::filesystem::path& path,
              std::span<const std::vector<Eigen::Vector2d>> polylines, double pixels_per_metre) {
  if (!IsFinitePositive(pixels_per_metre)) {
    throw Error(path.string() + ": SVG scale must be a positive number of pixels per metre");
  }
  // The drawing covers the walls and every polyline point, plus a margin.
  bool any = !map.empty();
  Eigen::Vector2d lo = map.bounds().min;
  Eigen::Vector2d hi = map.bounds().max;
  for (const auto& line : polylines) {
    for (const Eigen::Vector2d& p : line) {
      if (!p.allFinite()) continue;
      lo = any ? lo.cwiseMin(p) : p;
      hi = any ? hi.cwiseMax(p) : p;
      any = true;
    }
  }
  lo.array() -= kMarginMetres;
  hi.array() += kMarginMetres;
  const double scale = pixels_per_metre;
  const auto sx = [&](double x) { return Number((x - lo.x()) * scale); };
  const auto sy = [&](double y) { return Number((hi.y() - y) * scale); };  // SVG y points down

  std::ofstream out(path);
  if (!out) throw Error(path.string() + ": cannot open SVG file for writing");
  const std::string width = Number((hi.x() - lo.x()) * scale);
  const std::string height = Number((hi.y() - lo.y()) * scale);
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" viewBox=\"0 0 " << width << ' ' << height << "\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<g id=\"walls\" stroke=\"black\" stroke-width=\"" << Number(std::max(1.0, 0.04 * scale))
      << "\" stroke-linecap=\"round\">\n";
  for (const Segment& s : map.segments()) {
    out << "<line x1=\"" << sx(s.a.x()) << "\" y1=\"" << sy(s.a.y()) << "\" x2=\"" << sx(s.b.x())
        << "\" y2=\"" << sy(s.b.y()) << "\"/>\n";
  }
  out << "</g>\n";
  for (std::size_t i = 0; i < polylines.size(); ++i) {
    out << "<polyline fill=\"none\" stroke=\"" << kPalette[i % kPalette.size()]
        << "\" stroke-width=\"" << Number(std::max(1.0, 0.03 * scale))
        << "\" stroke-linejoin=\"round\" points=\"";
    bool first = true;
    for (const Eigen::Vector2d& p : polylines[i]) {
      if (!p.allFinite()) continue;
      out << (first ? "" : " ") << sx(p.x()) << ',' << sy(p.y());
      first = false;
    }
    out << "\"/>\n";
  }
  out << "</svg>\n";
  out.close();
  if (!out) throw Error(path.string() + ": error while writing SVG file");
}

}  // namespace evoslam
