#ifndef EVOSLAM_COMMON_REPORT_SLAM_OUTPUTS_H_
#define EVOSLAM_COMMON_REPORT_SLAM_OUTPUTS_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "common/report/localize_report.h"
#include "common/sensor/dataset.h"
#include "common/slam/slam_method.h"
#include "evoslam/service.pb.h"
#include "evoslam/slam.pb.h"

namespace evoslam {

// Everything a SLAM job hands back, as named files, in this order:
//   trajectory.txt, trajectory.tum  the result's poses;
//   odometry.txt                    the odometry at each scan mapped;
//   truth.txt                       the ground truth at each scan, when the scans have it;
//   map.yaml, map.pgm, map.png      the result's map, for map_server and as a picture;
//   map_trajectory.png              the map with the estimate, odometry, ground truth and each
//                                   loop closure as a line between its two poses;
//   pareto.csv, pareto.png          when the result has Pareto fronts: their members, and their
//                                   picture (pareto_csv.h, pareto_picture.h);
//   report.json, summary.txt        MakeSlamReport with the outputs listed, and its summary.
// The map pictures are drawn from the other files (run_pictures.h), as `evoslam plot` draws them;
// the Pareto picture from the result's fronts, under the map pictures' title. The result covers
// the log's first result.trajectory.size() scans. The same result gives the same bytes. Throws
// Error for a result with no poses, more poses than scans, a loop whose scans lie beyond its
// poses, or fronts that CheckParetoFronts refuses.
std::vector<proto::ResultFile> SlamOutputs(const Dataset& dataset, const proto::SlamParams& params,
                                           const SlamResult& result,
                                           const std::optional<NamedRelations>& relations,
                                           std::uint32_t threads);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_REPORT_SLAM_OUTPUTS_H_
