#include "common/util/available_memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <fstream>

namespace evoslam {
namespace {

TEST(ParseMemAvailableTest, ReadsTheLineInKibibytes) {
  EXPECT_EQ(ParseMemAvailable("MemTotal:       24576000 kB\nMemFree:          100 kB\n"
                              "MemAvailable:    2048 kB\nBuffers:   5 kB\n"),
            2048u * 1024);
  EXPECT_EQ(ParseMemAvailable("MemTotal:       24576000 kB\nMemFree:          100 kB\n"),
            std::nullopt);
  EXPECT_EQ(ParseMemAvailable("MemAvailable:\nBuffers: 5 kB\n"), std::nullopt);
}

TEST(FormatBytesTest, UsesDecimalUnitsWithTwoOrThreeDigits) {
  EXPECT_EQ(FormatBytes(512), "512 bytes");
  EXPECT_EQ(FormatBytes(12'345), "12 kB");
  EXPECT_EQ(FormatBytes(350'000'000), "350 MB");
  EXPECT_EQ(FormatBytes(1'440'000'000), "1.4 GB");
  EXPECT_EQ(FormatBytes(5'000'000'000'000'000), "5000 TB");
}

// The address-space limit (ulimit -v) bounds what the process can still allocate.
TEST(AvailableMemoryBytesTest, AnAddressSpaceLimitBoundsIt) {
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &saved), 0);
  if (saved.rlim_cur != RLIM_INFINITY || saved.rlim_max != RLIM_INFINITY) {
    GTEST_SKIP() << "the address space is limited already";
  }
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  ASSERT_TRUE(statm >> pages) << "this test needs /proc";
  const std::uint64_t mapped = pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
  // 64 MB above what is mapped, so that nothing done under it can fail for it; restored at once.
  constexpr std::uint64_t kRoom = 64'000'000;
  rlimit limited = saved;
  limited.rlim_cur = mapped + kRoom;
  ASSERT_EQ(setrlimit(RLIMIT_AS, &limited), 0);
  const auto available = AvailableMemoryBytes();
  ASSERT_EQ(setrlimit(RLIMIT_AS, &saved), 0);
  ASSERT_TRUE(available);
  EXPECT_LE(*available, kRoom);
  EXPECT_GT(*available, kRoom / 2);
}

}  // namespace
}  // namespace evoslam
