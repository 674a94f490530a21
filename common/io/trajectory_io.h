#ifndef EVOSLAM_COMMON_IO_TRAJECTORY_IO_H_
#define EVOSLAM_COMMON_IO_TRAJECTORY_IO_H_

#include <filesystem>
#include <span>
#include <vector>

#include "common/transform/pose2.h"

namespace evoslam {

struct StampedPose {
  double timestamp = 0.0;
  Pose2 pose;
};

// "t x y theta" per line, after a '#' header. Throws Error naming the path on failure.
void WriteTrajectoryText(std::span<const StampedPose> poses, const std::filesystem::path& path);

// TUM RGB-D format, "t x y z qx qy qz qw" per line: z = 0 and the quaternion of the heading.
void WriteTrajectoryTum(std::span<const StampedPose> poses, const std::filesystem::path& path);

// Reads either format (plain, gzip or bzip2): 4 fields a line for text, 8 for TUM, the same on
// every line; '#' comments and blank lines are ignored. A TUM orientation becomes its heading
// (the rotation about z). Malformed lines are an InputError with file and line.
std::vector<StampedPose> ReadTrajectory(const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_TRAJECTORY_IO_H_
