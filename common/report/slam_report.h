#ifndef EVOSLAM_COMMON_REPORT_SLAM_REPORT_H_
#define EVOSLAM_COMMON_REPORT_SLAM_REPORT_H_

#include <cstdint>
#include <optional>
#include <string>

#include "common/report/localize_report.h"
#include "common/sensor/dataset.h"
#include "common/slam/rss_slam.h"
#include "common/slam/slam_proto.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

proto::GlobalSearchRecord ToProto(const GlobalSearchRecord& search);
proto::SlamPhaseTimes ToProto(const SlamPhaseTimes& times);

// The odometry of the log's first `scans` scans, stamped with their timestamps: the trajectory
// SLAM starts from and corrects.
std::vector<StampedPose> ScanOdometry(const Dataset& dataset, std::size_t scans);

// The report of a SLAM run over the log's first result.trajectory.size() scans, its outputs list
// left empty: what was run, how long each phase took, the loops and global searches, and, for
// the estimate and for odometry alone, the errors against ground truth (when the scans have true
// poses) and against `relations` (when given; else ground truth's consecutive relations).
// Throws Error when the result has more poses than the log has scans.
proto::SlamReport MakeSlamReport(const Dataset& dataset, const proto::SlamParams& params,
                                 const RssSlamResult& result,
                                 const std::optional<NamedRelations>& relations,
                                 std::uint32_t threads);

// The few lines a person reads first: what ran, how long each phase took, the loops found, the
// global searches applied and the errors.
std::string FormatSlamSummary(const proto::SlamReport& report);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_SLAM_REPORT_H_
