#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/option_parsing.h"
#include "common/io/carmen_reader.h"
#include "common/sensor/dataset_summary.h"

namespace evoslam::cli {

void AddInfoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Describe a CARMEN log (plain, .gz or .bz2)");
  struct Args {
    std::string log;
    bool lenient = false;
  };
  auto args = std::make_shared<Args>();
  AddLogOption(cmd, "log", args->log, "CARMEN log to describe")->required();
  cmd->add_flag("--lenient", args->lenient, "skip malformed log lines and report how many");
  cmd->callback([args] {
    CarmenReadStats stats;
    const Dataset dataset = ReadCarmen(args->log, {.lenient = args->lenient}, &stats);
    std::printf("%s\n", args->log.c_str());
    std::printf("%s", FormatSummary(Summarize(dataset)).c_str());
    if (stats.skipped > 0) {
      std::printf("skipped %zu malformed lines (the first, line %zu: %s)\n", stats.skipped,
                  stats.first_skip_line, stats.first_skip_reason.c_str());
    }
  });
}

}  // namespace evoslam::cli
