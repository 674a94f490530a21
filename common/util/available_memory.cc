#include "common/util/available_memory.h"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <iterator>
#include <string>

namespace evoslam {
namespace {

std::optional<std::string> FileText(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The first decimal number of `text`; nullopt for none ("max" in a cgroup file).
std::optional<std::uint64_t> LeadingNumber(std::string_view text) {
  const auto digit = text.find_first_of("0123456789");
  if (digit == std::string_view::npos) return std::nullopt;
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data() + digit, text.data() + text.size(), value);
  if (error != std::errc()) return std::nullopt;
  return value;
}

void KeepLeast(std::optional<std::uint64_t>& least, std::optional<std::uint64_t> value) {
  if (value && (!least || *value < *least)) least = value;
}

// What the process has mapped, from /proc/self/statm's first field (in pages).
std::optional<std::uint64_t> MappedBytes() {
  const auto statm = FileText("/proc/self/statm");
  if (!statm) return std::nullopt;
  const auto pages = LeadingNumber(*statm);
  if (!pages) return std::nullopt;
  return *pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

// The folder of the process's cgroup (v2) under /sys/fs/cgroup, from /proc/self/cgroup's "0::"
// line; nullopt without cgroup v2.
std::optional<std::string> CgroupFolder() {
  const auto cgroup = FileText("/proc/self/cgroup");
  if (!cgroup) return std::nullopt;
  const auto at = cgroup->find("0::");
  if (at == std::string::npos || (at > 0 && (*cgroup)[at - 1] != '\n')) return std::nullopt;
  const auto end = cgroup->find('\n', at);
  return "/sys/fs/cgroup" + cgroup->substr(at + 3, end == std::string::npos ? end : end - at - 3);
}

}  // namespace

std::optional<std::uint64_t> ParseMemAvailable(std::string_view meminfo) {
  constexpr std::string_view kKey = "MemAvailable:";
  const auto at = meminfo.find(kKey);
  if (at == std::string_view::npos) return std::nullopt;
  const std::string_view rest = meminfo.substr(at + kKey.size());
  const auto kib = LeadingNumber(rest.substr(0, rest.find('\n')));
  if (!kib) return std::nullopt;
  return *kib * 1024;
}

std::optional<std::uint64_t> AvailableMemoryBytes() {
  std::optional<std::uint64_t> least;
  if (const auto meminfo = FileText("/proc/meminfo")) KeepLeast(least, ParseMemAvailable(*meminfo));
  if (const auto folder = CgroupFolder()) {
    const auto max = FileText(*folder + "/memory.max");
    const auto current = FileText(*folder + "/memory.current");
    if (max && current) {
      const auto limit = LeadingNumber(*max);  // none for "max"
      const auto used = LeadingNumber(*current);
      if (limit && used) KeepLeast(least, *limit > *used ? *limit - *used : 0);
    }
  }
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    if (const auto mapped = MappedBytes()) {
      KeepLeast(least, as.rlim_cur > *mapped ? as.rlim_cur - *mapped : 0);
    }
  }
  return least;
}

std::string FormatBytes(std::uint64_t bytes) {
  constexpr const char* kUnits[] = {"bytes", "kB", "MB", "GB", "TB"};
  double value = static_cast<double>(bytes);
  std::size_t unit = 0;
  while (value >= 1000.0 && unit + 1 < std::size(kUnits)) {
    value /= 1000.0;
    ++unit;
  }
  if (unit == 0) return fmt::format("{} bytes", bytes);
  return value < 10.0 ? fmt::format("{:.1f} {}", value, kUnits[unit])
                      : fmt::format("{:.0f} {}", value, kUnits[unit]);
}

}  // namespace evoslam
