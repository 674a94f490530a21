#ifndef EVOSLAM_COMMON_OPTIM_EVOLVE_H_
#define EVOSLAM_COMMON_OPTIM_EVOLVE_H_

#include <cstddef>
#include <limits>
#include <optional>

#include "common/optim/algorithm.h"
#include "common/optim/stop_criteria.h"

namespace evoslam {

// Advances an initialised algorithm by at most `max_generations` generations, checking the stop
// criteria before each one. Returns why the run stopped, or nullopt when it may go on.
std::optional<StopReason> Advance(
    const Problem& problem, Algorithm& algorithm, StopTracker& tracker, Rng& rng,
    std::size_t max_generations = std::numeric_limits<std::size_t>::max());

// A whole single-objective run: Initialize, then generations until a criterion stops it.
// Returns the best candidate ever evaluated.
OptimResult Minimize(const Problem& problem, Algorithm& algorithm, const StopCriteria& criteria,
                     Rng& rng);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_OPTIM_EVOLVE_H_
