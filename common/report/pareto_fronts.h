#ifndef EVOSLAM_COMMON_REPORT_PARETO_FRONTS_H_
#define EVOSLAM_COMMON_REPORT_PARETO_FRONTS_H_

#include <span>

#include "common/slam/slam_method.h"

namespace evoslam {

// Throws Error, naming the front, unless the fronts can be written and drawn: at least one;
// every front with the same objectives, at least one and each named (the CSV's columns); f with a
// row per objective and the chosen member among its columns; a start, when given, with a finite
// value per objective. Non-finite values of f pass: the CSV holds them as they are and the
// picture leaves them out.
void CheckParetoFronts(std::span<const ParetoFront> fronts);

// Whether the fronts are drawn relative to where their searches started, so that the fronts of
// searches that started far apart share one scale: when every front has a start, none of whose
// values is zero.
bool DrawnRelativeToStart(std::span<const ParetoFront> fronts);

// A value relative to where its search started, 1 + (value - start) / |start|: 1 at the start,
// lower being better as for the value itself; value / start for a positive start.
double RelativeToStart(double value, double start);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_PARETO_FRONTS_H_
