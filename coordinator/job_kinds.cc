#include "coordinator/job_kinds.h"

#include <string>

#include "common/localization/localize_params.h"
#include "common/service/job_inputs.h"
#include "common/slam/methods/slam_methods.h"
#include "common/util/error.h"
#include "coordinator/localize_job.h"
#include "coordinator/slam_job.h"

namespace evoslam {
namespace {

void PrepareLocalize(proto::JobSpec& spec) {
  if (!spec.has_localize()) throw Error("a localization job needs its parameters (localize)");
  if (spec.seed() != 0) spec.mutable_localize()->set_seed(spec.seed());
  if (spec.islands() != 0) spec.mutable_localize()->set_islands(spec.islands());
  if (spec.max_evaluations() != 0) {
    throw Error("a localization's budget is per scan: set its generations, not max_evaluations");
  }
  // The stored spec, and so the report, says what runs: parameters written before F2's
  // tolerance fields get the papers' tolerance.
  proto::LocalizeParams& localize = *spec.mutable_localize();
  if (!localize.has_f2_base_m()) localize.set_f2_base_m(FitnessParams{}.f2_base);
  if (!localize.has_f2_slope()) localize.set_f2_slope(FitnessParams{}.f2_slope);
  LocalizeOptionsFromProto(localize);  // throws Error naming a bad parameter
}

void PrepareSlam(proto::JobSpec& spec) {
  if (!spec.has_slam()) throw Error("a SLAM job needs its parameters (slam)");
  proto::SlamParams& slam = *spec.mutable_slam();
  if (spec.seed() != 0) slam.set_seed(spec.seed());
  if (spec.islands() != 0) FindSlamMethod(slam.method()).SetIslands(slam, spec.islands());
  if (!slam.has_log()) slam.set_log(spec.log().name());  // the report names the log
  if (spec.max_evaluations() != 0) {
    throw Error("a SLAM job's budget is its method's parameters, not max_evaluations");
  }
  if (!spec.map().sha256().empty() || !spec.map_image().sha256().empty()) {
    throw Error("a SLAM job builds its own map: it takes none");
  }
  ValidateSlamParams(slam);  // throws Error naming a bad parameter
}

}  // namespace

void PrepareJobSpec(proto::JobSpec& spec) {
  switch (spec.kind()) {
    case proto::JOB_KIND_LOCALIZE:
      return PrepareLocalize(spec);
    case proto::JOB_KIND_SLAM:
      return PrepareSlam(spec);
    default:
      throw Error("job kind " + std::to_string(spec.kind()) +
                  " is not one this coordinator runs (localize, SLAM)");
  }
}

std::vector<std::pair<const char*, proto::DatasetRef>> JobDatasets(const proto::JobSpec& spec) {
  std::vector<std::pair<const char*, proto::DatasetRef>> refs = {{"log", spec.log()}};
  if (spec.kind() == proto::JOB_KIND_LOCALIZE) refs.emplace_back("map", spec.map());
  if (!spec.map_image().sha256().empty()) refs.emplace_back("map image", spec.map_image());
  if (!spec.relations().sha256().empty()) refs.emplace_back("relations", spec.relations());
  return refs;
}

void CheckJobFileReferences(const proto::JobSpec& spec,
                            const std::function<std::string(const proto::DatasetRef&)>& content) {
  if (spec.kind() != proto::JOB_KIND_LOCALIZE || spec.localize().map_from_log()) return;
  if (IsMapYaml(spec.map())) CheckMapImageIsOwn(content(spec.map()), spec.map(), spec.map_image());
}

std::vector<proto::ResultFile> RunJobOfKind(const JobContext& context) {
  switch (context.spec.kind()) {
    case proto::JOB_KIND_LOCALIZE:
      return RunLocalizeJob(context);
    case proto::JOB_KIND_SLAM:
      return RunSlamJob(context);
    default:
      throw Error("job kind " + std::to_string(context.spec.kind()) + " cannot run here");
  }
}

}  // namespace evoslam
