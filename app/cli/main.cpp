// simsols — the SimSols executable.
//
//   simsols run SCENE.toml --out DIR     headless run (time series, dumps, checkpoints)
//   simsols run --resume DIR             continue a run from its last checkpoint
//   simsols campaign --out DIR           the paper's 20 direct shear tests (resumable)
//   simsols bench                        particle-steps per second and memory
//   simsols snapshot SCENE|CKPT --out F  one offscreen frame (PNG)
//   simsols lab [SCENE] [--script F]     the desktop lab (window)
//   simsols study accuracy|sensitivity|shape --out DIR   the measured studies
//   simsols plot ...                     several shear tests' curves on common axes
//
// Exit status: 0 success, 2 bad input (UsageError, SceneError, ReadError), 3 the
// OpenCL device or the renderer failed (DeviceError, RenderError), 4 the run
// ran away (NaN or a particle too fast; see solver/core/guard.h), 5 a result
// could not be written (IoError), 70 an internal error (any other exception:
// a fault of the program, reported as such, never as a device failure),
// 130 / 143 stopped by SIGINT / SIGTERM with a checkpoint (app/cli/interrupt.h).
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "render/gl/render_error.h"
#include "solver/common/did_you_mean.h"
#include "solver/common/errors.h"
#include "solver/core/guard.h"

int main(int argc, char** argv) {
  CLI::App app{"SimSols — a 3D virtual laboratory for granular materials (DEM on OpenCL)"};
  app.require_subcommand(1);
  std::map<CLI::App*, simsols::CommandRunner> runners;
  auto add = [&](simsols::CommandRunner (*f)(CLI::App&)) {
    const size_t before = app.get_subcommands({}).size();
    auto runner = f(app);
    runners[app.get_subcommands({})[before]] = std::move(runner);
  };
  add(simsols::add_run_command);
  add(simsols::add_bench_command);
  add(simsols::add_campaign_command);
  add(simsols::add_snapshot_command);
  add(simsols::add_lab_command);
  add(simsols::add_study_command);
  add(simsols::add_plot_command);
  add(simsols::add_calibrate_command);
  add(simsols::add_predict_command);
  // A mistyped command: named, with the closest one and the list (CLI11
  // alone says only that a subcommand is required).
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    if (std::find(names.begin(), names.end(), argv[1]) == names.end()) {
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      std::fprintf(stderr, "error: unknown command '%s'%s; the commands: %s (simsols --help)\n",
                   argv[1], simsols::did_you_mean(argv[1], names).c_str(), list.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  for (auto& [sub, run] : runners) {
    if (!sub->parsed()) continue;
    try {
      return run();
    } catch (const simsols::InputError& e) {  // UsageError, SceneError
      std::fprintf(stderr, "error: %s\n", e.what());
      return 2;
    } catch (const simsols::ReadError& e) {  // a malformed file no caller named
      std::fprintf(stderr, "error: a file could not be read: %s\n", e.what());
      return 2;
    } catch (const simsols::RunawayError& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 4;
    } catch (const simsols::IoError& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 5;
    } catch (const simsols::DeviceError& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 3;
    } catch (const simsols::render::RenderError& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      return 3;
    } catch (const std::exception& e) {
      std::fprintf(stderr,
                   "internal error: %s\n(a fault of SimSols, not of your input or device: "
                   "please report it with the command line)\n",
                   e.what());
      return 70;
    }
  }
  return 2;
}
