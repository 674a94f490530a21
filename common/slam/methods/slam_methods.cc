#include "common/slam/methods/slam_methods.h"

#include <array>
#include <string>

#include "common/slam/immune/immune_method.h"
#include "common/slam/rss/rss_method.h"
#include "common/slam/slam_params.h"
#include "common/util/error.h"

namespace evoslam {

const SlamMethod& FindSlamMethod(std::string_view name) {
  static const RssMethod rss;
  static const ImmuneMethod immune;
  static const std::array<const SlamMethod*, 2> methods = {&rss, &immune};
  for (const SlamMethod* method : methods) {
    if (method->name() == name) return *method;
  }
  throw Error("method '" + std::string(name) + "' is not a SLAM method (" + SlamMethodList() + ")");
}

void ValidateSlamParams(const proto::SlamParams& params) {
  const SlamMethod& method = FindSlamMethod(params.method());
  CheckOneMethodsParams(params);
  method.Validate(params);
}

proto::SlamParams CompleteSlamParams(const proto::SlamParams& params) {
  ValidateSlamParams(params);
  return WithDefaults(params);
}

}  // namespace evoslam
