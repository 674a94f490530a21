#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "common/report/run_pictures.h"

namespace evoslam::cli {
namespace {

namespace fs = std::filesystem;

struct PlotArgs {
  std::string run, compare, out;
};

void Plot(const PlotArgs& a) {
  const RunRecord run = ReadRun(a.run);
  if (a.compare.empty() && a.out.empty()) {
    for (const std::string& name : WriteRunPictures(run, run.dir)) {
      std::printf("wrote %s\n", (run.dir / name).string().c_str());
    }
    return;
  }
  std::optional<RunRecord> other;
  if (!a.compare.empty()) other = ReadRun(a.compare);
  const fs::path out = a.out.empty() ? run.dir / "compare.png" : fs::path(a.out);
  if (out.has_parent_path()) fs::create_directories(out.parent_path());
  WriteMapPicture(run.map, TrajectoryPicture(run, other ? &*other : nullptr), out);
  std::printf("wrote %s\n", out.string().c_str());
}

}  // namespace

void AddPlotCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "plot", "Redraw a run's pictures from its output folder, or draw it beside another run");
  auto a = std::make_shared<PlotArgs>();
  cmd->add_option("run", a->run, "the folder a slam or localize run wrote (its --out)")
      ->required()
      ->type_name("RUN_DIR");
  cmd->add_option("--compare", a->compare,
                  "another run's folder: its estimate is drawn beside this run's, into --out "
                  "(default RUN_DIR/compare.png)")
      ->type_name("OTHER_DIR");
  cmd->add_option("--out", a->out,
                  "write the map with the trajectories to this PNG, leaving RUN_DIR as it is "
                  "(default: redraw RUN_DIR's pictures in place)")
      ->type_name("FILE");
  cmd->callback([a] { Plot(*a); });
}

}  // namespace evoslam::cli
