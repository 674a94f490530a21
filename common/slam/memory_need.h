#ifndef EVOSLAM_COMMON_SLAM_MEMORY_NEED_H_
#define EVOSLAM_COMMON_SLAM_MEMORY_NEED_H_

#include <cstdint>
#include <optional>
#include <string>

namespace evoslam {

// The memory a SLAM run will take beyond what its process holds when it starts (the log read),
// estimated before it starts, and what takes it, in the user's terms: "its search map of
// 11201 x 15501 cells of 0.005 m (--resolution)".
struct MemoryNeed {
  std::uint64_t bytes = 0;
  std::string driver;
};

// A run over this is worth a word before it starts.
inline constexpr std::uint64_t kLargeRunBytes = 1'000'000'000;

// Throws Error, saying how much the run needs, what for and how much there is, when `need` is
// more than `available` (nullopt: unknown, nothing refused). Returns the warning to give when it
// is over kLargeRunBytes.
std::optional<std::string> CheckMemoryNeed(const MemoryNeed& need,
                                           std::optional<std::uint64_t> available);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_SLAM_MEMORY_NEED_H_
