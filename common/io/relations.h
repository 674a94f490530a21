#ifndef EVOSLAM_COMMON_IO_RELATIONS_H_
#define EVOSLAM_COMMON_IO_RELATIONS_H_

#include <filesystem>
#include <vector>

#include "common/transform/pose2.h"

namespace evoslam {

// A measured relative pose: the robot's pose at time t2 seen from its pose at time t1.
struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  Pose2 delta;
};

// Reads a relations file (Kuemmerle et al. 2009 format): "t1 t2 x y z roll pitch yaw" per line,
// of which the planar part x, y, yaw is kept. '#' comments and blank lines are ignored; plain,
// gzip and bzip2 files are accepted. Malformed lines are an InputError with file and line.
std::vector<Relation> ReadRelations(const std::filesystem::path& path);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_IO_RELATIONS_H_
