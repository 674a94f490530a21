#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_TRAJECTORY_WINDOW_PROBLEM_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_TRAJECTORY_WINDOW_PROBLEM_H_

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "common/optim/problem.h"
#include "common/slam/immune/correction_genes.h"
#include "common/slam/immune/evidence_grid.h"
#include "common/slam/immune/evidence_overlay.h"
#include "common/slam/immune/key_points.h"
#include "common/slam/immune/trajectory_segments.h"
#include "common/transform/pose2.h"
#include "evoslam/slam_params.pb.h"

namespace evoslam {

// The three variants of the method, which differ in the search alone.
enum class ImmuneVariant {
  kImmune,   // 004: three objectives, vaccination and immune selection
  kMoea,     // the same MOEA without vaccination and immune selection
  kDuckett,  // Duckett's GA: one objective, the weighted sum f1 + w2 f2 + w3 f3
};
ImmuneVariant ParseImmuneVariant(std::string_view name);  // throws Error listing the variants

// Duckett's fitness, f1 + occupied_weight f2 + empty_weight f3: the duckett variant's one
// objective, and what picks the member applied from the other variants' fronts.
double DuckettSum(double consistency, double occupied, double empty,
                  const proto::ImmuneSearchParams& search);

// A key point as one window sees it: where it is, and its sightings from the window's scans.
struct WindowKeyPoint {
  Eigen::Vector2d position;
  std::vector<KeyPointSighting> sightings;
};

// What a window's problem is built on; every reference must outlive the problem.
struct TrajectoryWindow {
  const SegmentedTrajectory* trajectory = nullptr;
  std::span<const EvidenceScan> scans;  // one per scan of the trajectory
  const EvidenceGrid* base = nullptr;   // the scans before the window, at their final poses
  std::size_t first_segment = 0;
  std::size_t segments = 0;
  Pose2 from;  // the corrected pose of the window's first scan
  std::vector<WindowKeyPoint> key_points;
};

// The corrections of a window of segments (004 §3.2), each candidate scored by the evidence grid
// of the base with the window's scans (one in scan_stride) put in at the poses it gives (eqs. 1-3):
// objectives f1, f2 and f3, or for Duckett's GA their weighted sum. An evaluation costs in
// proportion to the window's scans, whatever the base holds. The window's poses as they stand (no
// correction) are the first population's first member.
class TrajectoryWindowProblem : public Problem {
 public:
  TrajectoryWindowProblem(TrajectoryWindow window, const proto::ImmuneParams& params);
  ~TrajectoryWindowProblem() override;

  const Eigen::VectorXd& lower() const override { return genes_.lower(); }
  const Eigen::VectorXd& upper() const override { return genes_.upper(); }
  Encoding encoding() const override { return genes_.encoding(); }
  std::size_t objectives() const override;
  std::vector<Eigen::VectorXd> starts() const override;
  const Immunity* immunity() const override;
  void Evaluate(const Eigen::Ref<const Eigen::MatrixXd>& candidates,
                std::span<double> fitness) const override;

  const CorrectionGenes& genes() const { return genes_; }
  const TrajectoryWindow& window() const { return window_; }
  std::size_t first_scan() const;
  std::size_t last_scan() const;  // included
  // The poses of scans first_scan() to last_scan() under candidate x.
  void Poses(const Eigen::Ref<const Eigen::VectorXd>& x, std::span<Pose2> out) const;
  // The objectives of the base with the window's scans at x's poses.
  EvidenceObjectives Objectives(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // f1 of a grid of the scans of the window's segments `first` and `first + 1` (or `first`
  // alone, at the window's end) at x's poses, and nothing else: immune selection's local measure.
  double LocalConsistency(const Eigen::Ref<const Eigen::VectorXd>& x, std::size_t first) const;

 private:
  void WriteFitness(const EvidenceObjectives& o, std::span<double> out) const;
  // The objectives of x; an infinite consistency when x carries a scan off the grid, which
  // WriteFitness turns into infinite objectives: such a candidate is infeasible.
  EvidenceObjectives Score(const Eigen::Ref<const Eigen::VectorXd>& x, EvidenceOverlay& overlay,
                           std::vector<Pose2>& poses, std::vector<PlacedScan>& placed) const;

  TrajectoryWindow window_;
  ImmuneVariant variant_;
  proto::ImmuneSearchParams search_;
  std::size_t scan_stride_;  // the scans k with k % scan_stride_ == 0 build the grid
  CorrectionGenes genes_;
  EvidenceGrid empty_;  // nothing in it: the base of immune selection's local grids
  std::unique_ptr<const Immunity> immunity_;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_TRAJECTORY_WINDOW_PROBLEM_H_
