// The peak resident memory of `evoslam slam` over the real logs, run as a user runs it: the
// embedded service, the defaults, in a process of its own, so that its peak is the command's.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/util/temp_dir.h"
#include "tests/process_testing.h"

namespace evoslam {
namespace {

// Maps `log` (its .clf.bz2 in the data folder, scored against its relations where it has them)
// and reports the command's peak resident set, as /usr/bin/time -v does.
void BM_SlamPeakMemory(benchmark::State& state, const std::string& log) {
  const std::filesystem::path data(EVOSLAM_DATA_DIR);
  const std::filesystem::path path = data / (log + ".clf.bz2");
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("data absent: " + path.string()).c_str());
    return;
  }
  std::vector<std::string> argv = {std::string(EVOSLAM_BINARY_DIR) + "/cli/evoslam", "slam",
                                   "--log", path.string()};
  if (const auto relations = data / (log + ".relations"); std::filesystem::exists(relations)) {
    argv.insert(argv.end(), {"--relations", relations.string()});
  }
  const TempDir dir("evoslam-memory-bench");
  argv.insert(argv.end(), {"--out", (dir / "out").string()});
  long peak_kib = 0;
  for (auto _ : state) {
    testing::ChildProcess slam(argv, dir / "slam.log");
    const std::optional<int> status = slam.Wait(std::chrono::hours(1));
    if (slam.exit_code() != 0) {
      state.SkipWithError(("evoslam slam failed, " +
                           (status ? testing::ChildProcess::Describe(*status) : "timed out") +
                           ": " + slam.Log().substr(0, 500))
                              .c_str());
      return;
    }
    peak_kib = *slam.max_rss_kib();
  }
  state.counters["peak_rss"] =
      benchmark::Counter(static_cast<double>(peak_kib) * 1024.0, benchmark::Counter::kDefaults,
                         benchmark::Counter::kIs1024);
}
BENCHMARK_CAPTURE(BM_SlamPeakMemory, intel, std::string("intel"))
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_SlamPeakMemory, aces, std::string("aces"))
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_SlamPeakMemory, mit_csail, std::string("mit-csail"))
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace evoslam
