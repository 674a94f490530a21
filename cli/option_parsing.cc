#include "cli/option_parsing.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/util/error.h"

namespace evoslam::cli {
namespace {

// The comma-separated pieces of `text` ("" gives one empty piece).
std::vector<std::string_view> SplitCommas(std::string_view text) {
  std::vector<std::string_view> pieces;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    pieces.push_back(text.substr(begin, end - begin));
    if (end == text.size()) return pieces;
    begin = end + 1;
  }
}

template <typename T>
std::optional<T> ParseNumber(std::string_view text) {
  T v{};
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) return std::nullopt;
  }
  return v;
}

// A check that the text is a finite number for which `ok` holds.
CLI::Validator NumberValidator(bool (*ok)(double), const std::string& what,
                               const std::string& name) {
  return CLI::Validator(
      [ok, what](const std::string& text) -> std::string {
        const auto v = ParseNumber<double>(text);
        return v && ok(*v) ? "" : "'" + text + "' is not " + what;
      },
      name);
}

}  // namespace

Pose2 ParsePose(const std::string& text, const std::string& flag) {
  std::vector<double> values;
  for (const std::string_view piece : SplitCommas(text)) {
    const auto v = ParseNumber<double>(piece);
    if (!v) throw Error(flag + ": expected x,y,theta (three numbers), got '" + text + "'");
    values.push_back(*v);
  }
  if (values.size() != 3)
    throw Error(flag + ": expected x,y,theta (three numbers), got '" + text + "'");
  return Pose2(values[0], values[1], values[2]);
}

CLI::Validator PositiveNumber() {
  return NumberValidator([](double v) { return v > 0.0; }, "a positive number", "POSITIVE");
}

CLI::Validator NonNegativeNumber() {
  return NumberValidator([](double v) { return v >= 0.0; }, "a number >= 0", "NONNEGATIVE");
}

}  // namespace evoslam::cli
