#include <google/protobuf/util/json_util.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/job_client.h"
#include "cli/localize_args.h"
#include "cli/option_parsing.h"
#include "cli/service_session.h"
#include "common/engine/archipelago.h"
#include "common/util/counted.h"
#include "common/util/error.h"
#include "evoslam/localize.pb.h"

namespace evoslam::cli {
namespace {

struct TuneArgs {
  LocalizeArgs job;
  std::string island_counts = "1,2,4,8";
  std::size_t seeds = 3;
  std::size_t total_population = 40;
  std::optional<double> target;
};

struct TimedRun {
  double seconds = 0.0;
  double fitness = 0.0;
  std::uint64_t evaluations = 0;
};

struct CountResult {
  std::size_t islands = 0;
  std::size_t population = 0;  // per island
  std::vector<TimedRun> runs;
};

std::vector<std::size_t> ParseCounts(const std::string& text) {
  std::vector<std::size_t> counts;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    unsigned long n = 0;
    try {
      n = std::stoul(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || n < 1 || n > kMaxIslands) {
      throw CLI::ValidationError("--island-counts: '" + item + "' is not an island count (1 to " +
                                 std::to_string(kMaxIslands) + ")");
    }
    counts.push_back(n);
  }
  if (counts.empty()) throw CLI::ValidationError("--island-counts needs at least one count");
  return counts;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

proto::LocalizeReport ReportOf(const std::vector<proto::ResultFile>& files) {
  for (const proto::ResultFile& f : files) {
    if (f.name() != "report.json") continue;
    proto::LocalizeReport report;
    if (!google::protobuf::util::JsonStringToMessage(f.content(), &report).ok())
      throw Error("the job's report.json is unreadable");
    return report;
  }
  throw Error("the job returned no report.json");
}

void RunTune(const TuneArgs& t) {
  const std::vector<std::size_t> counts = ParseCounts(t.island_counts);
  std::vector<CountResult> results;
  for (const std::size_t n : counts) {
    LocalizeArgs a = t.job;
    a.optimizer = "island";
    a.given.insert("--optimizer");
    a.islands = n;
    // The same budget at every count: the total population is shared among the islands.
    a.population = std::max<std::size_t>(4, (t.total_population + n / 2) / n);
    a.given.insert("--population");
    CountResult r{n, a.population, {}};
    ServiceSession session(a.run.service, ChooseEmbeddedLayout(n, a.run.workers, a.run.threads));
    for (std::size_t s = 0; s < t.seeds; ++s) {
      a.seed = t.job.seed + s;
      const LocalizeOptions options = OptionsFrom(a);
      const auto start = std::chrono::steady_clock::now();
      const proto::JobSpec spec = JobFrom(a, options, session.client());
      const std::string id = session.client().Submit(spec);
      const proto::LocalizeReport report = ReportOf(FollowToResult(session.client(), id));
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      r.runs.push_back({seconds, report.mean_fitness(), report.evaluations()});
      spdlog::info("{} of {}, seed {}: {:.2f} s, mean fitness {:.6g}", Counted(n, "island"),
                   a.population, a.seed, seconds, report.mean_fitness());
    }
    results.push_back(std::move(r));
  }

  // Unless given, the target is what the best island count reaches, within 2 %.
  double best = std::numeric_limits<double>::infinity();
  for (const CountResult& r : results) {
    std::vector<double> f;
    for (const TimedRun& run : r.runs) f.push_back(run.fitness);
    best = std::min(best, Median(f));
  }
  const double target = t.target.value_or(best + 0.02 * std::abs(best));

  std::printf("islands  population/island  evaluations  time s  mean fitness  time to target s\n");
  std::optional<std::size_t> pick;
  double pick_time = std::numeric_limits<double>::infinity();
  for (const CountResult& r : results) {
    std::vector<double> seconds, fitness, reached;
    std::uint64_t evaluations = 0;
    for (const TimedRun& run : r.runs) {
      seconds.push_back(run.seconds);
      fitness.push_back(run.fitness);
      evaluations = std::max(evaluations, run.evaluations);
      if (run.fitness <= target) reached.push_back(run.seconds);
    }
    const bool all = reached.size() == r.runs.size();
    char ttt[64];
    if (all) {
      std::snprintf(ttt, sizeof ttt, "%.2f", Median(reached));
    } else {
      std::snprintf(ttt, sizeof ttt, "not reached (%zu/%zu)", reached.size(), r.runs.size());
    }
    std::printf("%7zu  %17zu  %11llu  %6.2f  %12.6g  %s\n", r.islands, r.population,
                static_cast<unsigned long long>(evaluations), Median(seconds), Median(fitness),
                ttt);
    if (all && Median(reached) < pick_time) {
      pick_time = Median(reached);
      pick = r.islands;
    }
  }
  std::printf("medians over %s; target mean fitness %.6g\n", Counted(t.seeds, "seed").c_str(),
              target);
  if (pick) {
    std::printf(
        "recommended for this host: --optimizer island --islands %zu (the fastest to reach the "
        "target)\n",
        *pick);
  } else {
    std::printf(
        "no island count reached the target in every seed; raise --generations or loosen "
        "--target\n");
  }
}

}  // namespace

void AddTuneCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "tune",
      "Run a localization job at several island counts with the same evaluation budget and "
      "recommend a count for this host");
  auto t = std::make_shared<TuneArgs>();
  AddLocalizeJobOptions(cmd, t->job, false);
  AddJobRunOptions(cmd, t->job.run);
  AddDeprecatedName(cmd, "--islands",
                    cmd->add_option("--island-counts", t->island_counts,
                                    "the island counts to try, comma-separated")
                        ->capture_default_str());
  cmd->add_option("--seeds", t->seeds, "runs per island count, seeds --seed, --seed + 1, ...")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  AddDeprecatedName(
      cmd, "--total-pop",
      cmd->add_option("--total-population", t->total_population,
                      "population of all islands together, shared evenly (at least 4 each)")
          ->capture_default_str()
          ->check(CLI::Range(4, 1000000)));
  cmd->add_option("--target", t->target,
                  "mean fitness per scan that counts as reached (default: the best count's "
                  "median, plus 2 %)");
  cmd->callback([t, cmd] {
    NoteGivenOptions(cmd, t->job);
    if (t->job.given.contains("--population") || t->job.given.contains("--optimizer")) {
      throw CLI::ValidationError(
          "tune sets --optimizer island and the population per island itself; use "
          "--total-population");
    }
    RunTune(*t);
  });
}

}  // namespace evoslam::cli
