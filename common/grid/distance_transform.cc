#include "common/grid/distance_transform.h"
#include "common/util/infinity.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

namespace evoslam {
namespace {

// One-dimensional, one-sided squared distance transform: out[q] = min over p >= q of
// (p - q)^2 + f[p]. Samples with f = infinity take no part, so the envelope arithmetic never sees
// infinities. Sites enter the lower envelope of parabolas from the far end, and each query, at the
// newest site, finds its parabola by binary search. `sites` and `bounds` are scratch of n and n
// + 1.
void OneSidedTransform1d(const double* f, double* out, int n, std::vector<int>& sites,
                         std::vector<double>& bounds) {
  // In mirrored coordinates u = n - 1 - p the sites arrive in increasing order, and the query at
  // u wants the envelope of the sites at or before u.
  const auto value = [&](int u) { return f[n - 1 - u]; };
  int k = -1;
  for (int u = 0; u < n; ++u) {
    const double fu = value(u);
    if (fu != kInfinity) {
      double s = -kInfinity;
      while (k >= 0) {
        const int p = sites[k];
        s = ((fu + static_cast<double>(u) * u) - (value(p) + static_cast<double>(p) * p)) /
            (2.0 * (u - p));
        if (s > bounds[k]) break;
        --k;
      }
      ++k;
      sites[k] = u;
      bounds[k] = k == 0 ? -kInfinity : s;
    }
    double& o = out[n - 1 - u];
    if (k < 0) {
      o = kInfinity;
      continue;
    }
    // The last envelope segment that starts at or before u.
    const auto first_after =
        std::upper_bound(bounds.begin(), bounds.begin() + k + 1, static_cast<double>(u));
    const int j = static_cast<int>(first_after - bounds.begin()) - 1;
    const double du = u - sites[j];
    o = du * du + value(sites[j]);
  }
}

void CheckSize(std::span<const std::uint8_t> seeds, int width, int height) {
  if (width < 0 || height < 0 ||
      seeds.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument("distance transform: raster size does not match");
  }
}

}  // namespace

void SquaredQuadrantDistanceTransform(std::span<const std::uint8_t> seeds, int width, int height,
                                      std::span<double> out) {
  CheckSize(seeds, width, height);
  if (out.size() != seeds.size()) {
    throw std::invalid_argument("quadrant distance transform: output size does not match");
  }
  const auto w = static_cast<std::size_t>(width);
  // Up each column (row by row, for the cache): the squared distance to the nearest seed at or
  // above.
  std::vector<double> nearest(w, kInfinity);
  for (int y = height - 1; y >= 0; --y) {
    const std::size_t row = static_cast<std::size_t>(y) * w;
    for (std::size_t x = 0; x < w; ++x) {
      if (seeds[row + x] != 0) nearest[x] = y;
      const double d = nearest[x] - y;
      out[row + x] = d * d;
    }
  }
  // Along each row, one-sidedly, from a copy of the row.
  std::vector<double> row(w);
  std::vector<int> sites(w);
  std::vector<double> bounds(w + 1);
  for (int y = 0; y < height; ++y) {
    double* const line = out.data() + static_cast<std::size_t>(y) * w;
    std::copy(line, line + w, row.begin());
    OneSidedTransform1d(row.data(), line, width, sites, bounds);
  }
}

}  // namespace evoslam
