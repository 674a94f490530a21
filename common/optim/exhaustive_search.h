#ifndef EVOSLAM_COMMON_OPTIM_EXHAUSTIVE_SEARCH_H_
#define EVOSLAM_COMMON_OPTIM_EXHAUSTIVE_SEARCH_H_

#include <Eigen/Core>
#include <functional>
#include <span>

#include "common/optim/problem.h"

namespace evoslam {

// Evaluates every point of a regular lattice over the box: `steps(j)` (>= 0) is the lattice
// spacing along coordinate j; points are lower + k * step up to the upper bound (both bounds
// included when the width is a multiple of the step), or the box centre when steps(j) is 0.
// The reference the stochastic optimisers are compared with; ties go to the first point found.
OptimResult RunExhaustiveSearch(const Problem& problem, const Eigen::VectorXd& steps);

// The same search with the batches evaluated by `evaluate` (elsewhere, for instance) instead of
// problem.Evaluate; the result does not depend on where they are evaluated.
using LatticeEvaluator = std::function<void(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                                            std::span<double> fitness)>;
OptimResult RunExhaustiveSearch(const Problem& problem, const Eigen::VectorXd& steps,
                                const LatticeEvaluator& evaluate);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_EXHAUSTIVE_SEARCH_H_
