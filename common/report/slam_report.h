#ifndef EVOSLAM_COMMON_REPORT_SLAM_REPORT_H_
#define EVOSLAM_COMMON_REPORT_SLAM_REPORT_H_

#include <cstdint>
#include <optional>
#include <string>

#include "common/report/localize_report.h"
#include "common/sensor/dataset.h"
#include "common/slam/slam_method.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

// The odometry of the log's first `scans` scans, stamped with their timestamps: the trajectory
// SLAM starts from and corrects.
std::vector<StampedPose> ScanOdometry(const Dataset& dataset, std::size_t scans);

// The report of a SLAM run over the log's first result.trajectory.size() scans, its outputs list
// left empty: what was run, how long it took, the loops, the method's own fields, and, for the
// estimate and for odometry alone, the errors against ground truth (when the scans have true
// poses) and against `relations` (when given; else ground truth's consecutive relations).
// Throws Error when the result has more poses than the log has scans.
proto::SlamReport MakeSlamReport(const Dataset& dataset, const proto::SlamParams& params,
                                 const SlamResult& result,
                                 const std::optional<NamedRelations>& relations,
                                 std::uint32_t threads);

// The few lines a person reads first: what ran and how long it took, the method's own lines,
// the loops found and the errors.
std::string FormatSlamSummary(const proto::SlamReport& report);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_SLAM_REPORT_H_
