#ifndef EVOSLAM_COMMON_IO_CARMEN_WRITER_H_
#define EVOSLAM_COMMON_IO_CARMEN_WRITER_H_

#include <filesystem>

#include "common/sensor/dataset.h"

namespace evoslam {

// Writes a dataset as a plain CARMEN text log that ReadCarmen reads back to the same dataset:
// a header comment, the PARAMs, then ODOM and laser messages merged by timestamp (each kind
// keeping its own order), with a TRUEPOS after every scan that has a true pose.
//
// Front scans go out as FLASER and rear scans as RLASER when those messages can carry their
// geometry (the beam layout ReadCarmen assumes for their count, and the range_max it would give
// them); otherwise, and for kRobotLaser scans, as ROBOTLASER1 (front) or ROBOTLASER2 (rear), which
// carry their own geometry but only one pose, so there the scan's odometry is not kept. Ranges
// and poses are printed with the fewest digits that read back to the same float/double,
// timestamps with 6 decimals (microseconds, as CARMEN does). range_min is not part of any CARMEN
// message and reads back as 0.
//
// Throws Error naming the path when the file cannot be written or the dataset holds something
// CARMEN cannot express (non-finite or negative ranges, non-finite poses, hostnames or PARAM
// names with whitespace).
void WriteCarmen(const Dataset& dataset, const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_CARMEN_WRITER_H_
