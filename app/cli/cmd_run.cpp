// simsols run: a headless experiment from a scene file, or its resumption.
//
// Order matters for "nothing half-written": the scene is loaded and
// validated and the kernels are built before the output folder is touched.
// Outputs in DIR: scene.toml (the file as given), scene.resolved.toml (the
// exact scene used, explicit particles), series.csv, particles_<step>.csv,
// paraview/ (the ParaView series, solver/io/paraview.h),
// checkpoint.bin (latest; `--resume DIR` continues from it bit for bit).
// When a step runs away (guard.h) the run stops there: fault.txt says at
// which step and which particle, fault_checkpoint.bin holds the state just
// before, and the exit status is 4.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "solver/apparatus/run_profile.h"
#include "solver/core/engine_options.h"
#include "solver/io/checkpoint.h"
#include "app/cli/commands.h"
#include "app/experiment/test_title.h"
#include "solver/scene/contact_model.h"
#include "solver/common/errors.h"
#include "render/view/frames.h"
#include "app/cli/interrupt.h"
#include "solver/io/output.h"
#include "solver/io/paraview.h"
#include "app/cli/video.h"
#include "app/experiment/progress.h"
#include "app/experiment/run_cost.h"
#include "solver/io/scene_toml.h"
#include "app/experiment/apparatus_report.h"
#include "app/experiment/apparatus_run.h"
#include "app/experiment/specimen_report.h"
#include "solver/core/simulation.h"
#include "solver/core/slots.h"

namespace simsols {
namespace {

struct RunOptions {
  std::string scene_path;
  std::string out_dir;
  bool resume = false;
  std::string precision;
  std::string profile = "paper";  // --profile (run_profile.h)
  double duration = 0;
  long long stop_after = 0;  // stop (with a checkpoint) after this many steps of this invocation
  std::string stop_at;       // stop (with a checkpoint) at the end of this stage of the test
  bool quiet = false;
  bool explain = false;       // print the compiled effect slots and exit
  std::string frames_dir;     // --frames: PNG frames every `frames_every` steps
  long long frames_every = 0;
  std::string video;          // --video: the frames encoded by ffmpeg (video.h)
  int fps = 30;
  FrameFlags frame;
};

// `run --frames DIR --every N`: one PNG every N steps, named by step. For a
// shear test the displacement field counts from the start of shearing.
class FrameSeries {
 public:
  FrameSeries(const RunOptions& opt, const EngineOptions& engine)
      : flags_(flags_with_environment(opt.frame)), dir_(opt.frames_dir), every_(opt.frames_every),
        exporter_(FrameOptions::resolve(flags_), engine) {}
  // The device that shares the exporter's GL context: the run's.
  const std::shared_ptr<Device>& device() const { return exporter_.device(); }
  // `caption`: the test's state for the picture (LoadingProgramme::caption),
  // empty for a plain run.
  void after_steps(Simulation& sim, bool shearing, const std::string& caption = {}) {
    if (!attached_) {
      exporter_.attach(sim, flags_);
      std::filesystem::create_directories(dir_);
      std::fprintf(stderr, "[frames] every %lld steps into %s; %s\n", every_, dir_.c_str(),
                   exporter_.describe().c_str());
      attached_ = true;
      next_ = sim.steps();  // a first frame now
    }
    if (shearing && !shearing_) exporter_.set_reference();
    shearing_ = shearing;
    if (sim.steps() < next_) return;
    exporter_.set_caption(test_title(sim.scene()), caption);
    char name[64];
    std::snprintf(name, sizeof name, "frame_%09lld.png", static_cast<long long>(sim.steps()));
    exporter_.write((std::filesystem::path(dir_) / name).string());
    next_ = (sim.steps() / every_ + 1) * every_;
  }
  long long every() const { return every_; }

 private:
  static FrameFlags flags_with_environment(FrameFlags f) {
    gl_from_environment(f);
    return f;
  }

  FrameFlags flags_;
  std::string dir_;
  long long every_;
  FrameExporter exporter_;
  bool attached_ = false, shearing_ = false;
  long long next_ = 0;
};

std::int64_t every(double interval, double dt, std::int64_t fallback) {
  if (interval <= 0) return fallback;
  return std::max<std::int64_t>(1, std::llround(interval / dt));
}

std::string step_name(const char* stem, std::int64_t step, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%09lld.%s", stem, static_cast<long long>(step), ext);
  return buf;
}

// The particles' CSV (dump_csv) and the ParaView series (dump_vtk) of this step.
void dump(Simulation& sim, const std::filesystem::path& dir, ParaviewSeries* paraview) {
  if (sim.scene().outputs.dump_csv)
    write_particles_csv(dir / step_name("particles", sim.steps(), "csv"), sim.snapshot());
  if (paraview) paraview->write(sim);
}

// --precision overrides numerics.precision.
void apply_precision(const RunOptions& opt, Scene& scene) {
  if (const auto p = precision_flag(opt.precision)) scene.numerics.precision = *p;
}

// `run SCENE --explain`: the slots the scene compiles, no run, no output folder.
int explain(const RunOptions& opt) {
  if (opt.scene_path.empty())
    throw UsageError("missing_field", "", 0, "SCENE", "--explain needs a scene file");
  Scene scene = read_scene(opt.scene_path);  // only reads: nothing is placed
  apply_precision(opt, scene);
  const KernelConfig config = make_kernel_config(scene, *open_command_device());
  std::printf("%s", explain_effects(scene, config).c_str());
  return 0;
}

struct Cadence {
  std::int64_t total = 0, series = 1, dump = 0, checkpoint = 0;
};

Cadence cadence(const Simulation& sim, const RunOptions& opt) {
  const Scene& scene = sim.scene();
  const double dt = sim.dt();
  // --duration also extends (or shortens) a resumed run
  const double duration = opt.duration > 0 ? opt.duration : scene.numerics.duration;
  Cadence c;
  c.total = static_cast<std::int64_t>(std::ceil(duration / dt - 1e-9));
  c.series = every(scene.outputs.series_interval, dt, std::max<std::int64_t>(1, c.total / 1000));
  c.dump = every(scene.outputs.dump_interval, dt, 0);
  c.checkpoint = every(scene.outputs.checkpoint_interval, dt, 0);
  return c;
}

void print_run_header(Simulation& sim, const Cadence& c, bool resumed) {
  const Scene& scene = sim.scene();
  std::fprintf(stderr,
               "[run] %s: %d particles, %d walls, %s on %s\n"
               "[run] dt = %.4g s (%.3g x Rayleigh %.4g s), %lld steps, kernel build %.2f s\n",
               scene.name.c_str(), sim.model().particles(), sim.model().walls(),
               sim.model().config().double_precision ? "double" : "float",
               sim.model().device().description().c_str(), sim.dt(),
               sim.dt() / sim.model().rayleigh_dt(), sim.model().rayleigh_dt(),
               static_cast<long long>(c.total), sim.model().program().build_seconds());
  if (resumed)
    std::fprintf(stderr, "[run] resumed at step %lld, t = %.6g s\n",
                 static_cast<long long>(sim.steps()), sim.time());
  print_cost("run", run_cost(sim, double(std::max<std::int64_t>(0, c.total - sim.steps()))));
}

// A scene without a loading programme: steps to numerics.duration, with the
// time series, dumps and checkpoints its [outputs] ask for.
int run_plain(Simulation& sim, const RunOptions& opt, FrameSeries* frames,
              const InterruptScope& interrupt) {
  const std::filesystem::path dir = opt.out_dir;
  const Cadence c = cadence(sim, opt);
  print_run_header(sim, c, opt.resume);
  std::vector<std::string> wall_names;
  for (const Wall& w : sim.scene().walls) wall_names.push_back(w.name);
  TimeSeries series((dir / "series.csv").string(), wall_names, opt.resume ? sim.steps() : -1);
  auto record = [&] {
    series.append(sim.time(), sim.steps(), sim.observe(), sim.wall_reactions(),
                  wall_points(sim.model(), sim.state()));
  };
  std::optional<ParaviewSeries> paraview;
  if (sim.scene().outputs.dump_vtk) paraview.emplace(dir / "paraview", opt.resume ? sim.steps() : -1);
  ParaviewSeries* pv = paraview ? &*paraview : nullptr;
  const auto checkpoint = [&] {
    series.flush();
    save_checkpoint(sim, (dir / "checkpoint.bin").string());
  };
  if (!opt.resume) {
    record();
    if (c.dump > 0) dump(sim, dir, pv);
  }
  if (frames) frames->after_steps(sim, false);
  Progress progress("run", c.total, sim.dt(), sim.model().particles(), opt.quiet);
  const std::int64_t start = sim.steps();
  bool stopped = false;
  // A runaway is noticed at the guard's next look (a list check, its next
  // copy, or any reading below) and leaves the simulation at the step before.
  try {
    while (sim.steps() < c.total && !(stopped = interrupt.requested())) {
      sim.advance(1);
      const std::int64_t s = sim.steps();
      if (s % c.series == 0 || s == c.total) record();
      if (c.dump > 0 && s % c.dump == 0) dump(sim, dir, pv);
      if (c.checkpoint > 0 && s % c.checkpoint == 0) checkpoint();
      if (frames) frames->after_steps(sim, false);
      progress.update(s);
      if (opt.stop_after > 0 && s - start >= opt.stop_after && s < c.total) {
        stopped = true;
        break;
      }
    }
    sim.check();
  } catch (const RunawayError& e) {
    progress.finish(sim.steps());
    series.flush();
    save_fault(sim, dir, e);
    throw;
  }
  progress.finish(sim.steps());
  checkpoint();
  if (!stopped && (c.dump == 0 || sim.steps() % c.dump != 0)) dump(sim, dir, pv);
  if (sim.state().late_builds > 0)
    std::fprintf(stderr,
                 "warning: %lld neighbour-list checks found a particle beyond skin/2 (lists may "
                 "have missed contacts); raise numerics.skin or lower the time step\n",
                 static_cast<long long>(sim.state().late_builds));
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sim.hash()));
  const bool interrupted = interrupt.requested() && sim.steps() < c.total;
  std::printf("%s at step %lld, t = %.6g s; state hash %s; results in %s\n",
              interrupted ? "interrupted" : stopped ? "stopped" : "finished",
              static_cast<long long>(sim.steps()), sim.time(), hash, dir.string().c_str());
  if (stopped) std::printf("  %s\n", resume_hint(dir.string()).c_str());
  return interrupted ? interrupt.exit_status() : 0;
}

void check_flags(const RunOptions& opt) {
  if (opt.out_dir.empty())
    throw UsageError("missing_field", "--out",
                     "--out DIR is required (the folder for the results)");
  if (!opt.frames_dir.empty() && opt.frames_every <= 0)
    throw UsageError("missing_field", "--every",
                     "--frames needs --every N (steps between frames, > 0)");
  if (opt.frames_dir.empty() && opt.frames_every > 0)
    throw UsageError("missing_field", "--frames",
                     "--every needs --frames DIR (the folder for the PNG frames)");
  if (!opt.video.empty() && opt.frames_dir.empty())
    throw UsageError("missing_field", "--frames", "--video needs --frames DIR --every N (its frames)");
  if (!opt.video.empty() && !opt.video.ends_with(".mp4"))
    throw UsageError("out_of_range", "--video", "'" + opt.video + "': the video is an MP4 file, name it *.mp4");
  if (opt.duration != 0 && !(opt.duration > 0 && std::isfinite(opt.duration)))
    throw UsageError("out_of_range", "--duration", "must be a finite time > 0 s");
}

// The scene of a new run, read (not yet placed), with the command line's
// overrides, validated.
Scene read_run_scene(const RunOptions& opt) {
  if (opt.scene_path.empty())
    throw UsageError("missing_field", "", 0, "SCENE", "a scene file is required (or --resume)");
  Scene scene = read_scene(opt.scene_path);
  apply_precision(opt, scene);
  const RunProfile& profile = run_profile(opt.profile);
  const ProfileApplied applied = apply_profile(scene, profile, opt.scene_path);
  if (!profile.neutral() && !opt.quiet)
    std::printf("profile %s: Young's moduli x %.3g (kappa = %.0f at the normal stress)\n",
                opt.profile.c_str(), applied.stiffness_scale, applied.kappa);
  if (opt.duration != 0) scene.numerics.duration = opt.duration;
  validate_scene(scene, scene.source_path);
  FrameOptions::resolve(opt.frame, &scene);  // a bad [view] is refused even without --frames
  if (const ApparatusKind* kind = apparatus_kind(scene); kind && opt.duration != 0)
    throw UsageError("conflicting_keys", "--duration",
                     std::string(kind->test_noun) + "'s loading programme sets its duration (see [" +
                         kind->name + "])");
  return scene;
}

// --resume: the checkpoint in DIR, verified, with the driver state it carries.
std::unique_ptr<Simulation> load_resume(const std::filesystem::path& dir,
                                        const std::shared_ptr<Device>& device, std::string* extra) {
  const auto ck = dir / "checkpoint.bin";
  if (!std::filesystem::exists(ck)) {
    std::string hint = "no checkpoint to resume from. A shear test writes one every minute of wall "
                       "time, a plain run at output.checkpoint_interval, both at the end, at "
                       "--stop-after and when stopped with Ctrl-C or kill";
    if (std::filesystem::exists(dir / "scene.toml"))
      hint += "; this run stopped before its first: start it again with 'simsols run " +
              (dir / "scene.toml").string() + " --out " + dir.string() + "'";
    throw SceneError("io", ck.string(), 0, "--resume", hint);
  }
  return load_checkpoint(device, ck.string(), extra);
}

ProgrammeRunOptions programme_options(const RunOptions& opt, const std::shared_ptr<Device>& device,
                                      FrameSeries* frames, const InterruptScope& interrupt) {
  ProgrammeRunOptions o;
  o.device = device;
  o.out_dir = opt.out_dir;
  o.quiet = opt.quiet;
  o.stop_after = opt.stop_after;
  o.stop_at = opt.stop_at;
  o.stop_requested = interrupt.stop_function();
  if (frames) {
    o.chunk_steps = std::min(2000LL, frames->every());
    o.after_chunk = [frames](Simulation& s, const LoadingProgramme& test) {
      frames->after_steps(s, test.measuring(), test.caption());
    };
  }
  return o;
}

// The test's result lines; the exit status (that of an interrupt when one stopped it).
int finish_test(const TestRun& run, const RunOptions& opt, const InterruptScope& interrupt) {
  std::printf("%s", test_result_text(run, opt.out_dir).c_str());
  return run.state.interrupted ? interrupt.exit_status() : 0;
}

int run_scene(const RunOptions& opt) {
  if (opt.explain) return explain(opt);
  check_flags(opt);
  if (opt.resume && programme_finished(opt.out_dir)) {
    std::printf("the test in %s finished already (summary.txt): nothing to resume\n",
                opt.out_dir.c_str());
    return 0;
  }
  std::optional<Scene> scene;
  if (!opt.resume) scene = read_run_scene(opt);  // a bad scene before any device or GL work
  // With --frames the exporter opens the device, sharing its GL context
  // where it can.
  const EngineOptions engine = engine_options_from_environment();
  std::unique_ptr<FrameSeries> frames;
  if (!opt.frames_dir.empty()) frames = std::make_unique<FrameSeries>(opt, engine);
  const std::shared_ptr<Device> device = frames ? frames->device() : Device::open(engine);
  const std::filesystem::path dir = opt.out_dir;
  InterruptScope interrupt;
  std::unique_ptr<Simulation> sim;
  std::string extra;
  if (opt.resume) sim = load_resume(dir, device, &extra);
  const ProgrammeRunOptions programme = programme_options(opt, device, frames.get(), interrupt);
  if (sim && sim->scene().has_apparatus())
    return finish_test(resume_test(std::move(sim), extra, programme), opt, interrupt);
  if (scene && scene->has_apparatus()) {
    // the specimen prepared first when the scene asks it (Ctrl-C stops that too)
    const auto log = [&](const std::string& line) {
      if (!opt.quiet) std::fprintf(stderr, "[prepare] %s\n", line.c_str());
    };
    try {
      return finish_test(run_scene_test(*scene, programme, log), opt, interrupt);
    } catch (const PreparationStopped& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return interrupt.exit_status();
    }
  }
  if (!opt.stop_at.empty())
    throw UsageError("conflicting_keys", "--stop-at",
                     "the scene has no apparatus, so no stages to stop at (use --stop-after N)");
  if (!sim) {
    place_scene(*scene);
    sim = std::make_unique<Simulation>(device, *scene);
    std::filesystem::create_directories(dir);
    write_file_atomic((dir / "scene.toml").string(), scene->source_text);
    write_file_atomic((dir / "scene.resolved.toml").string(), to_toml(*scene));
  }
  return run_plain(*sim, opt, frames.get(), interrupt);
}

// The run, then its frames as a video when --video asks.
int run(const RunOptions& opt) {
  const int status = run_scene(opt);
  if (!opt.video.empty() && !opt.explain) std::printf("  %s\n", encode_video(opt.frames_dir, opt.video, opt.fps).message.c_str());
  return status;
}

}  // namespace

namespace {

// --stop-at's help: each kind's stages, from the registry.
std::string stop_at_help() {
  std::string text = std::string("Stop at the end of this stage of the test, with a checkpoint "
                                 "(resume with --resume): ") +
                     kPreparedStage + " (every test: its specimen prepared, nothing loaded), or "
                     "the stages of";
  for (const ApparatusKind& k : apparatus_kinds()) {
    text += std::string(&k == apparatus_kinds().data() ? " " : "; ") + k.test_noun + ": " + k.stages;
  }
  return text;
}

}  // namespace

CommandRunner add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Run a scene headless and write its results");
  cmd->add_option("scene", opt->scene_path, "Scene file (TOML), see docs/scene-format.md");
  cmd->add_option("--out,-o", opt->out_dir, "Output folder (required unless --explain)");
  cmd->add_flag("--explain", opt->explain,
                "Print the effect slots compiled in, the -D build options and the per-contact "
                "history size, and exit without running");
  cmd->add_flag("--resume", opt->resume, "Continue the run in --out from its last checkpoint");
  cmd->add_option("--precision", opt->precision, "Override numerics.precision: float or double");
  cmd->add_option("--profile", opt->profile,
                  "paper (the scene's settings, default) or fast (a shear box: dt 0.5 x Rayleigh, "
                  "I 2e-3; docs/accuracy.md)");
  cmd->add_option("--duration", opt->duration, "Override numerics.duration (s, > 0)");
  cmd->add_option("--stop-after", opt->stop_after,
                  "Stop after this many steps (a checkpoint is written; resume with --resume)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--stop-at", opt->stop_at, stop_at_help());
  cmd->add_flag("--quiet,-q", opt->quiet, "No progress line");
  cmd->add_option("--frames", opt->frames_dir, "Write PNG frames (offscreen) into this folder");
  cmd->add_option("--every", opt->frames_every, "Steps between frames (with --frames)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--video", opt->video,
                  "With --frames: encode the frames into this MP4 file with ffmpeg (when installed)");
  cmd->add_option("--fps", opt->fps, "Frames per second of --video (default 30)")->check(CLI::Range(1, 240));
  add_frame_flags(cmd, opt->frame);
  return [opt] { return run(*opt); };
}

}  // namespace simsols
