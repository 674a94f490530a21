#ifndef EVOSLAM_COMMON_UTIL_AVAILABLE_MEMORY_H_
#define EVOSLAM_COMMON_UTIL_AVAILABLE_MEMORY_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace evoslam {

// The memory a new allocation of this process can still get, in bytes: the least of the
// machine's available memory (/proc/meminfo's MemAvailable), what its cgroup's memory.max leaves
// above memory.current, and the address-space limit (ulimit -v) above what the process has
// mapped. Nullopt when none of them can be read.
std::optional<std::uint64_t> AvailableMemoryBytes();

// MemAvailable of a /proc/meminfo text, in bytes; nullopt without that line.
std::optional<std::uint64_t> ParseMemAvailable(std::string_view meminfo);

// A byte count as people read it: "1.4 GB", "350 MB", "12 kB" (decimal units, two or three
// significant digits).
std::string FormatBytes(std::uint64_t bytes);

}  // namespace evoslam

#endif  // EVOSLAM_COMMON_UTIL_AVAILABLE_MEMORY_H_
