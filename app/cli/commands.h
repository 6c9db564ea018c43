// The headless commands of the simsols executable. Each registers its
// options on a CLI11 subcommand and returns the process exit status:
// 0 success, 2 bad input (scene, flag), 3 device or I/O failure.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace simsols {

using CommandRunner = std::function<int()>;

CommandRunner add_run_command(CLI::App& app);
CommandRunner add_bench_command(CLI::App& app);
CommandRunner add_campaign_command(CLI::App& app);
CommandRunner add_snapshot_command(CLI::App& app);
CommandRunner add_lab_command(CLI::App& app);
CommandRunner add_study_command(CLI::App& app);
CommandRunner add_plot_command(CLI::App& app);

}  // namespace simsols
