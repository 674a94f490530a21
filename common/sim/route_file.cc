#include "common/sim/route_file.h"

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "common/io/line_reader.h"
#include "common/io/text_fields.h"
#include "common/util/error.h"

namespace evoslam {

std::vector<Eigen::Vector2d> ReadRoute(const std::filesystem::path& path) {
  LineReader reader(path);
  std::vector<Eigen::Vector2d> route;
  std::vector<std::string_view> fields;
  while (const std::optional<std::string_view> line = reader.Next()) {
    SplitFields(StripHashComment(*line), &fields);
    if (fields.empty()) continue;
    if (fields.size() != 2) {
      throw InputError(reader.source(), reader.line_number(),
                       "expected a waypoint as 2 numbers \"x y\", found " +
                           std::to_string(fields.size()) + " fields");
    }
    Eigen::Vector2d p;
    for (int k = 0; k < 2; ++k) {
      const std::optional<double> value = ParseDouble(fields[k]);
      if (!value || !std::isfinite(*value)) {
        throw InputError(reader.source(), reader.line_number(),
                         std::string(k == 0 ? "x" : "y") + " is \"" + std::string(fields[k]) +
                             "\", expected a finite number");
      }
      p[k] = *value;
    }
    route.push_back(p);
  }
  if (route.size() < 2) {
    throw InputError(reader.source(), reader.line_number(),
                     "a route needs at least two waypoints, found " + std::to_string(route.size()));
  }
  return route;
}

}  // namespace evoslam
