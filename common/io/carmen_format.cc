#include "common/io/carmen_format.h"

#include "common/io/text_fields.h"
#include "common/util/finite_checks.h"

namespace evoslam {

double FlaserAngleIncrement(std::size_t beams) {
  if (beams < 2) return 0.0;
  const std::size_t intervals = beams % 2 == 1 ? beams - 1 : beams;
  return std::numbers::pi / static_cast<double>(intervals);
}

bool IsRangeMaxParam(std::string_view name, bool rear) {
  return rear ? name == "laser_rear_laser_max_range" || name == "robot_rear_laser_max"
              : name == "laser_front_laser_max_range" || name == "robot_front_laser_max";
}

std::optional<double> ParseRangeMaxParam(std::string_view value) {
  const std::optional<double> parsed = ParseDouble(value);
  if (!parsed || !IsFinitePositive(*parsed)) return std::nullopt;
  return parsed;
}

double CarmenRangeMax(const std::vector<std::pair<std::string, std::string>>& params, bool rear) {
  std::optional<double> front;
  std::optional<double> back;
  for (const auto& [name, value] : params) {
    const std::optional<double> parsed = ParseRangeMaxParam(value);
    if (!parsed) continue;
    if (IsRangeMaxParam(name, false)) front = parsed;
    if (IsRangeMaxParam(name, true)) back = parsed;
  }
  if (rear && back) return *back;
  return front.value_or(kCarmenDefaultRangeMax);
}

}  // namespace evoslam
