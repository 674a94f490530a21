#ifndef EVOSLAM_CLI_COMMANDS_H_
#define EVOSLAM_CLI_COMMANDS_H_

#include <CLI/CLI.hpp>

namespace evoslam::cli {

// Each registers one subcommand of `evoslam`; its callback runs the command and throws
// evoslam::Error on bad input, which main reports.
void AddInfoCommand(CLI::App& app);
void AddSimulateCommand(CLI::App& app);
void AddLocalizeCommand(CLI::App& app);
void AddSlamCommand(CLI::App& app);
void AddEvalCommand(CLI::App& app);
void AddKeygenCommand(CLI::App& app);
// jobs, status, watch, result, cancel, workers: managing jobs on a running coordinator.
void AddJobCommands(CLI::App& app);
void AddTuneCommand(CLI::App& app);
void AddPlotCommand(CLI::App& app);

}  // namespace evoslam::cli

#endif  // EVOSLAM_CLI_COMMANDS_H_
