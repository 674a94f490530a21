#include "common/slam/immune/evidence_scan.h"

#include <algorithm>
#include <cmath>

#include "common/slam/immune/evidence_model.h"

namespace evoslam {

EvidenceScan::EvidenceScan(const LaserScan& scan, const proto::EvidenceGridParams& params) {
  const std::size_t stride = params.beam_stride();
  beams_.reserve(scan.size() / stride + 1);
  for (std::size_t i = 0; i < scan.size(); i += stride) {
    if (!scan.is_return(i)) continue;
    const double range = scan.ranges[i];
    const double angle = scan.angle(i);
    const bool cut = range > params.max_range_m();
    EvidenceBeam beam{.x = std::cos(angle),
                      .y = std::sin(angle),
                      .range_m = std::min(range, params.max_range_m()),
                      .occupied_units = cut ? 0 : EvidenceUnits(ReadingMass(params, range))};
    total_range_m_ += beam.range_m;
    max_range_m_ = std::max(max_range_m_, beam.range_m);
    beams_.push_back(beam);
  }
}

}  // namespace evoslam
