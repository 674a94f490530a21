#ifndef EVOSLAM_COMMON_REPORT_PARETO_TESTING_H_
#define EVOSLAM_COMMON_REPORT_PARETO_TESTING_H_

// For tests: Pareto fronts as a multi-objective method hands them back.

#include <string>
#include <utility>
#include <vector>

#include "common/slam/slam_method.h"

namespace evoslam::testing {

// The immune method's objectives.
inline std::vector<std::string> ImmuneObjectives() {
  return {"consistency", "occupied cells", "empty cells"};
}

// A front of the members given as each one's objective values, its columns in f.
inline ParetoFront MakeFront(std::string label, const std::vector<std::vector<double>>& members,
                             std::vector<double> start, std::size_t chosen,
                             std::vector<std::string> objectives = ImmuneObjectives()) {
  const auto rows = static_cast<Eigen::Index>(objectives.size());
  ParetoFront front{.label = std::move(label),
                    .objectives = std::move(objectives),
                    .f = Eigen::MatrixXd(rows, static_cast<Eigen::Index>(members.size())),
                    .start = std::move(start),
                    .chosen = chosen};
  for (std::size_t m = 0; m < members.size(); ++m) {
    for (std::size_t o = 0; o < members[m].size(); ++o) {
      front.f(static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(m)) = members[m][o];
    }
  }
  return front;
}

// Two windows' fronts, each of three members that trade consistency for occupied cells, all
// below where their windows started.
inline std::vector<ParetoFront> TwoWindowFronts() {
  return {MakeFront("window 0: scans 0-120",
                    {{80.0, 1000.0, 5000.0}, {90.0, 950.0, 5100.0}, {100.0, 900.0, 4900.0}},
                    {120.0, 1100.0, 5200.0}, 1),
          MakeFront("window 1: scans 120-241",
                    {{20.0, 300.0, 2000.0}, {25.0, 280.0, 1950.0}, {30.0, 260.0, 1990.0}},
                    {40.0, 310.0, 2100.0}, 2)};
}

}  // namespace evoslam::testing

#endif  // EVOSLAM_COMMON_REPORT_PARETO_TESTING_H_
