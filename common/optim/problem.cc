#include "common/optim/problem.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/util/error.h"

namespace evoslam {

void Conform(const Problem& problem, Eigen::Ref<Eigen::VectorXd> x) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  switch (problem.encoding()) {
    case Encoding::kReal:
      for (Eigen::Index j = 0; j < x.size(); ++j) x(j) = std::clamp(x(j), lo(j), hi(j));
      return;
    case Encoding::kInteger:
      for (Eigen::Index j = 0; j < x.size(); ++j)
        x(j) = std::clamp(std::round(x(j)), std::ceil(lo(j)), std::floor(hi(j)));
      return;
    case Encoding::kBinary:
      for (Eigen::Index j = 0; j < x.size(); ++j) x(j) = x(j) >= 0.5 ? 1.0 : 0.0;
      return;
  }
}

void ValidateProblem(const Problem& problem) {
  const Eigen::VectorXd& lo = problem.lower();
  const Eigen::VectorXd& hi = problem.upper();
  if (lo.size() == 0) throw Error("problem has no coordinates");
  if (hi.size() != lo.size()) throw Error("problem bounds differ in length");
  if (problem.objectives() == 0) throw Error("problem has no objectives");
  for (Eigen::Index j = 0; j < lo.size(); ++j) {
    const std::string where = "coordinate " + std::to_string(j);
    if (!std::isfinite(lo(j)) || !std::isfinite(hi(j)))
      throw Error("problem bounds of " + where + " are not finite");
    if (lo(j) > hi(j)) throw Error("problem bounds of " + where + " are inverted");
    if (problem.encoding() == Encoding::kInteger && std::ceil(lo(j)) > std::floor(hi(j)))
      throw Error("integer " + where + " has no integer between its bounds");
    if (problem.encoding() == Encoding::kBinary && (lo(j) != 0.0 || hi(j) != 1.0))
      throw Error("binary " + where + " must have bounds [0, 1]");
  }
}

}  // namespace evoslam
