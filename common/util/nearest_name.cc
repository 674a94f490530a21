#include "common/util/nearest_name.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace evoslam {

std::size_t EditDistance(std::string_view a, std::string_view b) {
  // The dynamic programme over prefixes, two rows back so that a swap of neighbours is one edit:
  // row[j] is the distance from a's first i characters to b's first j.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    before.swap(previous);
    previous.swap(row);
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({previous[j] + 1, row[j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        row[j] = std::min(row[j], before[j - 2] + 1);
      }
    }
  }
  return row[b.size()];
}

std::optional<std::string> NearestName(std::string_view typed, std::span<const std::string> names) {
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  for (const std::string& name : names) {
    const std::size_t d = EditDistance(typed, name);
    const std::size_t allowed = std::max<std::size_t>(1, std::max(typed.size(), name.size()) / 3);
    if (d > allowed) continue;
    if (!best || d < best_distance) {
      best = name;
      best_distance = d;
    }
  }
  if (best || typed.empty()) return best;
  // A beginning of one name alone ("office" of "office-cluster") is what was meant too.
  std::optional<std::string> only;
  for (const std::string& name : names) {
    if (!name.starts_with(typed)) continue;
    if (only) return std::nullopt;
    only = name;
  }
  return only;
}

}  // namespace evoslam
