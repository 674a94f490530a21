#ifndef EVOSLAM_COMMON_SLAM_IMMUNE_IMMUNE_METHOD_H_
#define EVOSLAM_COMMON_SLAM_IMMUNE_IMMUNE_METHOD_H_

#include "common/slam/slam_method.h"

namespace evoslam {

// Paper 004's multi-objective trajectory optimisation with immunity as a SlamMethod: RunImmuneSlam
// from the log's odometry, its checkpoints after every window in proto::ImmuneCheckpoint, the
// evidence grid as the map, and each window's final front for the outputs.
class ImmuneMethod final : public SlamMethod {
 public:
  std::string_view name() const override { return "immune"; }
  void Validate(const proto::SlamParams& params) const override;
  std::size_t Islands(const proto::SlamParams& params) const override;
  void SetIslands(proto::SlamParams& params, std::uint32_t islands) const override;
  MemoryNeed PeakMemory(const Dataset& dataset, const proto::SlamParams& params) const override;
  SlamResult Run(const Dataset& dataset, const proto::SlamParams& params,
                 const SlamHooks& hooks) const override;
  std::shared_ptr<const Problem> TaskProblem(const Dataset& dataset,
                                             const proto::ProblemSpec& task) const override;
  std::vector<SlamFlag> Flags() const override;
  std::string Summary(const proto::SlamReport& report) const override;
};

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_IMMUNE_IMMUNE_METHOD_H_
