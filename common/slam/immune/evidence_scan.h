#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_SCAN_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_SCAN_H_

#include <cstdint>
#include <span>
#include <vector>

#include "common/sensor/laser_scan.h"
#include "common/transform/pose2.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// One beam as the evidence grid reads it, in the laser's frame.
struct EvidenceBeam {
  double x = 0;  // unit direction
  double y = 0;
  double range_m = 0;  // cut to max_range_m
  // The occupied reading where the return ends, in kEvidenceUnit; 0 for a beam cut to
  // max_range_m, which gives empty evidence only.
  std::uint32_t occupied_units = 0;
};

// A scan prepared once for the evidence grid: all of it that does not depend on where it is put.
// Keeps one beam in params.beam_stride, and of those only returns (a beam that returned nothing
// says nothing here); ranges beyond max_range_m are cut to it. `params` must be the grid's and
// valid (ValidateEvidenceGridParams).
class EvidenceScan {
 public:
  EvidenceScan(const LaserScan& scan, const proto::EvidenceGridParams& params);

  std::span<const EvidenceBeam> beams() const { return beams_; }
  // The summed length of the beams, m: what tracing the scan costs.
  double total_range_m() const { return total_range_m_; }
  // The longest beam, m: how far from the laser the scan reaches.
  double max_range_m() const { return max_range_m_; }

 private:
  std::vector<EvidenceBeam> beams_;
  double total_range_m_ = 0;
  double max_range_m_ = 0;
};

// A prepared scan and the laser's pose in the world.
struct PlacedScan {
  const EvidenceScan* scan = nullptr;
  Pose2 pose;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_EVIDENCE_SCAN_H_
