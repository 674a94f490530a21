#include "common/sensor/dataset.h"

#include <algorithm>

namespace evoslam {

bool Dataset::has_ground_truth() const {
  return !scans.empty() &&
         std::all_of(scans.begin(), scans.end(), [](const LaserScan& s) { return s.true_pose; });
}

}  // namespace evoslam
