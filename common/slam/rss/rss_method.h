#ifndef EVOSLAM_COMMON_SLAM_RSS_RSS_METHOD_H_
#define EVOSLAM_COMMON_SLAM_RSS_RSS_METHOD_H_

#include "common/slam/slam_method.h"

namespace evoslam {

// Paper 002's reduced-search-space SLAM as a SlamMethod: RunRssSlam, its checkpoints in
// proto::RssCheckpoint, its global searches' islands on workers as GlobalSearchSpec tasks.
class RssMethod final : public SlamMethod {
 public:
  std::string_view name() const override { return "rss"; }
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

#endif  // EVOSLAM_COMMON_SLAM_RSS_RSS_METHOD_H_
