#include "common/slam/memory_need.h"

#include <fmt/format.h>

#include "common/util/available_memory.h"
#include "common/util/error.h"

namespace evoslam {

std::optional<std::string> CheckMemoryNeed(const MemoryNeed& need,
                                           std::optional<std::uint64_t> available) {
  if (available && need.bytes > *available) {
    throw Error(fmt::format(
        "the run needs about {} of memory for {}, more than the {} available; map at a coarser "
        "resolution",
        FormatBytes(need.bytes), need.driver, FormatBytes(*available)));
  }
  if (need.bytes <= kLargeRunBytes) return std::nullopt;
  return fmt::format("the run will take about {} of memory for {}", FormatBytes(need.bytes),
                     need.driver);
}

}  // namespace evoslam
