#include "common/report/pareto_fronts.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/util/error.h"

namespace evoslam {
namespace {

std::string FrontName(const ParetoFront& front, std::size_t index) {
  return front.label.empty() ? fmt::format("Pareto front {}", index)
                             : fmt::format("Pareto front {} ({})", index, front.label);
}

void CheckFront(const ParetoFront& front, std::size_t index, const ParetoFront& first) {
  const std::string name = FrontName(front, index);
  const std::size_t objectives = front.objectives.size();
  if (front.objectives != first.objectives) {
    throw Error(
        fmt::format("{} has the objectives [{}], but front 0 has [{}]: the fronts of one "
                    "run share their objectives",
                    name, fmt::join(front.objectives, ", "), fmt::join(first.objectives, ", ")));
  }
  if (static_cast<std::size_t>(front.f.rows()) != objectives) {
    throw Error(
        fmt::format("{}: f has {} rows for the {} objectives", name, front.f.rows(), objectives));
  }
  if (front.chosen >= static_cast<std::size_t>(front.f.cols())) {
    throw Error(fmt::format("{}: the chosen member {} is not among its {} members", name,
                            front.chosen, front.f.cols()));
  }
  if (!front.start.empty() && front.start.size() != objectives) {
    throw Error(fmt::format("{}: the start has {} values for the {} objectives", name,
                            front.start.size(), objectives));
  }
  if (!std::ranges::all_of(front.start, [](double v) { return std::isfinite(v); })) {
    throw Error(
        fmt::format("{}: the start [{}] is not finite", name, fmt::join(front.start, ", ")));
  }
}

}  // namespace

void CheckParetoFronts(std::span<const ParetoFront> fronts) {
  if (fronts.empty()) throw Error("Pareto fronts: there are none to write");
  const ParetoFront& first = fronts.front();
  if (first.objectives.empty()) throw Error(FrontName(first, 0) + " names no objectives");
  if (std::ranges::any_of(first.objectives, [](const std::string& o) { return o.empty(); })) {
    throw Error(fmt::format("{}: an objective has no name, in [{}]", FrontName(first, 0),
                            fmt::join(first.objectives, ", ")));
  }
  for (std::size_t i = 0; i < fronts.size(); ++i) CheckFront(fronts[i], i, first);
}

bool DrawnRelativeToStart(std::span<const ParetoFront> fronts) {
  return std::ranges::all_of(fronts, [](const ParetoFront& front) {
    return !front.start.empty() &&
           std::ranges::none_of(front.start, [](double v) { return v == 0.0; });
  });
}

double RelativeToStart(double value, double start) {
  return 1.0 + (value - start) / std::abs(start);
}

}  // namespace evoslam
