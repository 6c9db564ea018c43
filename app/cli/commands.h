// The headless commands of the simsols executable. Each registers its
// options on a CLI11 subcommand and returns the process exit status
// (main.cpp maps the error types of solver/common/errors.h onto them).
//
// The commands are the edge: only here are flags and the environment
// read (SIMSOLS_CL_DEVICE, SIMSOLS_LANES, SIMSOLS_LOCAL_SIZE,
// SIMSOLS_CL_OPTIONS into EngineOptions; SIMSOLS_GL into --gl's default).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "solver/scene/scene.h"

namespace simsols {

class Device;
struct FrameFlags;

using CommandRunner = std::function<int()>;

// The OpenCL device of a command that draws nothing, opened with the
// options the environment asks for.
std::shared_ptr<Device> open_command_device();
// A --precision value: nullopt when not given; a UsageError naming `flag`
// and the allowed names when not a precision.
std::optional<Precision> precision_flag(const std::string& value,
                                        const std::string& flag = "--precision");
// --gl when given, else SIMSOLS_GL when set, else "auto": `gl` holds the
// flag's value, `given` whether it was on the command line.
void gl_from_environment(std::string& gl, bool given);
void gl_from_environment(FrameFlags& flags);

CommandRunner add_run_command(CLI::App& app);
CommandRunner add_bench_command(CLI::App& app);
CommandRunner add_campaign_command(CLI::App& app);
CommandRunner add_snapshot_command(CLI::App& app);
CommandRunner add_lab_command(CLI::App& app);
CommandRunner add_study_command(CLI::App& app);
CommandRunner add_plot_command(CLI::App& app);
CommandRunner add_calibrate_command(CLI::App& app);
CommandRunner add_predict_command(CLI::App& app);

}  // namespace simsols
