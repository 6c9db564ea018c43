// simsols snapshot: one offscreen frame of a scene or a checkpoint.
//
//   simsols snapshot SCENE.toml|checkpoint.bin --out frame.png [--view ...]
//       [--size WxH] [--color-by FIELD] [--mode opaque|transparent|chains]
//       [--chains] [--threshold R] [--range MIN:MAX] [--steps N] [--gl ...]
//
// The scene's [view] section sets defaults for the flags not given.
// A scene is drawn as built (a shear box: its specimen as placed, before
// settling), after --steps steps if given; a checkpoint as saved. Flags are
// checked, the output folder must exist and the name end in .png, before
// any GL or OpenCL work; the PNG is written atomically.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "solver/apparatus/registry.h"
#include "solver/core/engine_options.h"
#include "solver/io/checkpoint.h"
#include "solver/common/input_file.h"
#include "app/cli/commands.h"
#include "app/experiment/specimen_report.h"
#include "app/experiment/programme_run.h"
#include "app/experiment/test_title.h"
#include "solver/common/errors.h"
#include "render/view/frames.h"
#include "solver/io/scene_toml.h"
#include "solver/core/simulation.h"

namespace simsols {
namespace {

struct SnapshotOptions {
  std::string input;
  std::string out;
  long long steps = 0;
  FrameFlags frame;
};

void check_output_path(const std::string& out, const char* flag) {
  namespace fs = std::filesystem;
  const fs::path p(out);
  if (p.extension() != ".png")
    throw UsageError("bad_flag", flag, "'" + out + "' must end in .png");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir))
    throw UsageError("io", out, 0, flag, "the folder '" + dir.string() + "' does not exist");
}

// The caption of a checkpoint's test: its programme restored from the
// checkpoint's driver state. Empty for a run without an apparatus, and for
// a state this reader does not know (a lab session's): the picture is then
// drawn without the test's quantities, never refused for them.
std::string test_caption(Simulation& sim, const std::string& state) {
  const Scene& s = sim.scene();
  if (!s.has_apparatus()) return "";
  try {
    const std::unique_ptr<ApparatusProgramme> test = make_programme(sim);
    restore_programme(*test, state, "");
    return test->caption();
  } catch (const std::exception&) {
    return "";
  }
}

int snapshot(const SnapshotOptions& opt) {
  FrameFlags flags = opt.frame;
  gl_from_environment(flags);
  FrameOptions frame = FrameOptions::resolve(flags);
  check_output_path(opt.out, "--out");
  if (!std::filesystem::exists(opt.input))
    throw SceneError("io", opt.input, 0, "SCENE_OR_CHECKPOINT", "no such file");
  const bool checkpoint = require_scene_or_checkpoint(opt.input, "a scene (TOML) or a checkpoint") ==
                          InputKind::Checkpoint;
  if (checkpoint) verify_checkpoint(opt.input);  // a damaged file before any GL work
  Scene scene;
  if (!checkpoint) {
    scene = load_scene(opt.input);  // errors before any GL work
    frame = FrameOptions::resolve(flags, &scene);
  }

  // Before the simulation: it opens the device that shares its GL context.
  FrameExporter exporter(frame, engine_options_from_environment());
  std::string programme;  // a checkpoint's test state
  std::unique_ptr<Simulation> sim =
      checkpoint ? load_checkpoint(exporter.device(), opt.input, &programme)
                 : std::make_unique<Simulation>(exporter.device(), scene);
  if (opt.steps > 0) sim->advance(opt.steps);
  exporter.attach(*sim, flags);
  exporter.set_caption(test_title(sim->scene()), checkpoint && opt.steps == 0 ? test_caption(*sim, programme) : "");
  frame = FrameOptions::resolve(flags, &sim->scene());  // as attach() applied it
  exporter.write(opt.out);
  std::fprintf(stderr, "[snapshot] %s\n", exporter.describe().c_str());
  std::printf("wrote %s (%dx%d, %d beads, step %lld)\n", opt.out.c_str(), frame.width,
              frame.height, sim->model().particles(), static_cast<long long>(sim->steps()));
  if (frame.alioscopy)
    std::printf("  interleaved for the 8-view display; views and grid beside it (%s_view0..7.png, "
                "%s_grid.png)\n",
                std::filesystem::path(opt.out).stem().c_str(),
                std::filesystem::path(opt.out).stem().c_str());
  return 0;
}

}  // namespace

CommandRunner add_snapshot_command(CLI::App& app) {
  auto opt = std::make_shared<SnapshotOptions>();
  CLI::App* cmd = app.add_subcommand("snapshot", "Render one frame of a scene or checkpoint (PNG)");
  cmd->add_option("input", opt->input, "Scene file (TOML) or checkpoint.bin")->required();
  cmd->add_option("--out,-o", opt->out, "Output PNG file")->required();
  cmd->add_option("--steps", opt->steps, "Advance this many steps first")->check(CLI::NonNegativeNumber);
  add_frame_flags(cmd, opt->frame);
  return [opt] { return snapshot(*opt); };
}

}  // namespace simsols
