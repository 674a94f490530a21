#ifndef EVOSLAM_COMMON_REPORT_RUN_PICTURES_H_
#define EVOSLAM_COMMON_REPORT_RUN_PICTURES_H_

#include <filesystem>
#include <string>
#include <vector>

#include "common/io/trajectory_io.h"
#include "common/localization/map_model.h"
#include "common/report/map_picture.h"

namespace evoslam {

// A run's output folder as its pictures see it: what ran and how well (report.json), the map it
// built or localized in, and its trajectories. The outputs draw their pictures from the files
// they have just written, so that `evoslam plot` on the folder draws the same pictures.
struct RunRecord {
  std::filesystem::path dir;
  bool slam = false;  // else a localization
  std::string title;  // the log, what ran, and the error when known
  std::string error;  // the error alone, "1.40 cm aligned RMS"; empty when unknown
  MapModel map;
  std::vector<StampedPose> estimate;
  std::vector<StampedPose> odometry;  // a SLAM run's, at each scan
  std::vector<StampedPose> truth;     // when the log has ground truth
  std::vector<LoopLink> loops;        // a SLAM run's
};

// Reads what the pictures need from the folder a slam or localize run wrote (its --out):
// report.json, trajectory.txt, the map (map.yaml with map.pgm, or a localization's map.lines),
// a SLAM run's odometry.txt, and truth.txt when the report gives errors against ground truth.
// Throws Error naming the folder and the file it lacks, or the file it cannot read.
RunRecord ReadRun(const std::filesystem::path& dir);

// The map with the run's trajectories and loops; given another run, its estimate beside this
// one's, each named by its folder and error in the legend.
MapPictureContent TrajectoryPicture(const RunRecord& run, const RunRecord* compared = nullptr);

// Writes the run's pictures into `dir` and returns their names: for a SLAM run map.png (the map
// alone) and map_trajectory.png, for a localization map.png (the map with the trajectories).
std::vector<std::string> WriteRunPictures(const RunRecord& run, const std::filesystem::path& dir);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_RUN_PICTURES_H_
