#ifndef EVOSLAM_COMMON_REPORT_PARETO_CSV_H_
#define EVOSLAM_COMMON_REPORT_PARETO_CSV_H_

#include <span>
#include <string>

#include "common/slam/slam_method.h"

namespace evoslam {

// The fronts as CSV text, for reading into a spreadsheet or a script: a '#' line saying what the
// file holds, a header `front,label,member,<each objective>,chosen`, then a line per member of
// every front, front by front: the front's index (from 0, in the order the searches ran) and
// label, the member's index, its value of each objective (the shortest text that reads back as
// the same double; "nan" and "inf" as they are), and chosen, 1 for the member the result applies
// and else 0. A label or objective name holding a comma, a quote or a line break is quoted as RFC
// 4180 has it; lines end in "\n". Throws Error as CheckParetoFronts does.
std::string ParetoCsv(std::span<const ParetoFront> fronts);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_PARETO_CSV_H_
