#ifndef EVOSLAM_COMMON_ENGINE_PRESETS_H_
#define EVOSLAM_COMMON_ENGINE_PRESETS_H_

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/engine/algorithm_spec.h"
#include "common/optim/stop_criteria.h"

namespace evoslam {

// The settings a paper ran an algorithm with, under one name, so that experiments can say
// "as in 003" and mean the same numbers everywhere. docs/engine.md lists them with their sources,
// including the values the papers leave out and what we chose instead.
struct Preset {
  std::string name;
  std::string source;  // the paper, and where in it
  AlgorithmSpec algorithm;
  StopCriteria stop;
};

std::span<const Preset> Presets();
// Throws Error listing the valid names.
const Preset& FindPreset(std::string_view name);
std::vector<std::string> PresetNames();

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_ENGINE_PRESETS_H_
