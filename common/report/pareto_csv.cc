#include "common/report/pareto_csv.h"

#include <string_view>

#include "common/io/text_fields.h"
#include "common/report/pareto_fronts.h"

namespace evoslam {
namespace {

// The text as one CSV field: as it is, or quoted with its quotes doubled where it holds what
// would end the field.
std::string CsvField(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

}  // namespace

std::string ParetoCsv(std::span<const ParetoFront> fronts) {
  CheckParetoFronts(fronts);
  std::string csv =
      "# The Pareto fronts of the run's multi-objective searches, all objectives minimised: a line "
      "per member; chosen is 1 for the member the result applies\n";
  csv += "front,label,member";
  for (const std::string& objective : fronts.front().objectives) csv += ',' + CsvField(objective);
  csv += ",chosen\n";
  for (std::size_t i = 0; i < fronts.size(); ++i) {
    const ParetoFront& front = fronts[i];
    const std::string label = CsvField(front.label);
    for (Eigen::Index m = 0; m < front.f.cols(); ++m) {
      csv += std::to_string(i) + ',' + label + ',' + std::to_string(m);
      for (Eigen::Index o = 0; o < front.f.rows(); ++o) csv += ',' + FormatShortest(front.f(o, m));
      csv += static_cast<std::size_t>(m) == front.chosen ? ",1\n" : ",0\n";
    }
  }
  return csv;
}

}  // namespace evoslam
