#include "app/experiment/programme_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "app/experiment/grading_plots.h"
#include "app/experiment/specimen_report.h"
#include "app/experiment/progress.h"
#include "app/experiment/run_cost.h"
#include "solver/apparatus/registry.h"
#include "solver/io/checkpoint.h"
#include "solver/io/output.h"
#include "solver/io/paraview.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kWallKey = "\nwall_seconds_so_far ";

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

void save(Simulation& sim, ProgrammeOutputs& out, const fs::path& dir, double wall) {
  out.save_rows(dir);
  save_checkpoint(sim, (dir / "checkpoint.bin").string(), driver_state(out.programme(), wall));
}

void print_header(const ProgrammeRunOptions& opt, Simulation& sim, ProgrammeOutputs& out) {
  if (opt.quiet) return;
  std::fprintf(stderr, "[%s] %s: %d beads, dt = %.4g s (%.3g x Rayleigh), %s on %s; %s\n",
               opt.label.c_str(), sim.scene().name.c_str(), sim.model().particles(), sim.dt(),
               sim.dt() / sim.model().rayleigh_dt(),
               sim.model().config().double_precision ? "double" : "float",
               sim.model().device().description().c_str(), out.describe().c_str());
  const LoadingProgramme::StepCount c = out.programme().step_count();
  print_cost(opt.label, run_cost(sim, c.total - c.done));
}

void warn_late_builds(Simulation& sim) {
  if (sim.state().late_builds > 0)
    std::fprintf(stderr,
                 "warning: %lld neighbour-list checks found a bead beyond skin/2 (contacts may "
                 "have been missed); raise numerics.skin or lower the time step\n",
                 static_cast<long long>(sim.state().late_builds));
}

// packing.txt once the specimen has settled, and its line.
void report_packing(Simulation& sim, const fs::path& dir, const ProgrammeRunOptions& opt) {
  const Specimen* specimen = sim.scene().specimen();
  if (!specimen) return;
  const Packing p = measure_specimen(sim);
  const Preparation& prep = specimen->preparation;
  write_file_atomic((dir / "packing.txt").string(), packing_text(p, prep));
  if (opt.quiet) return;
  char dr[40] = "";
  if (prep.e_min)
    std::snprintf(dr, sizeof dr, ", D_r = %.3f", relative_density(p.void_ratio, *prep.e_min, *prep.e_max));
  std::fprintf(stderr,
               "[%s] settled: e = %.4f to the top at %.3f mm, %.4f in the slab below%s, %.2f contacts per "
               "grain, fabric anisotropy %.3f\n",
               opt.label.c_str(), p.bulk_void_ratio, 1e3 * p.height, p.void_ratio, dr, p.coordination,
               p.fabric_anisotropy);
}

}  // namespace

ProgrammeRunState drive_programme(Simulation& sim, ProgrammeOutputs& out,
                                  const ProgrammeRunOptions& opt, double wall_before) {
  const fs::path dir = opt.out_dir;
  LoadingProgramme& test = out.programme();
  print_header(opt, sim, out);
  ProgrammeProgress progress(opt.label, opt.quiet, opt.later_particle_steps,
                             sim.model().particles());
  progress.start(test);
  const auto start = Clock::now();
  auto last_checkpoint = start;
  const long long first = sim.steps();
  bool announced = test.measuring();
  ProgrammeRunState state;
  std::optional<ParaviewSeries> paraview;
  const Outputs& o = sim.scene().outputs;
  if (o.dump_vtk) paraview.emplace(dir / "paraview", opt.resume ? sim.steps() : -1);
  const long long dump_every = o.dump_interval > 0 ? std::max(1LL, std::llround(o.dump_interval / sim.dt())) : 0;
  long long next_dump = dump_every > 0 ? (sim.steps() / dump_every + (opt.resume ? 1 : 0)) * dump_every : -1;
  // --stop-at prepared: the prepared specimen checkpointed, nothing loaded
  if (opt.stop_at == kPreparedStage && !opt.resume) state.stopped_after = kPreparedStage;
  while (!test.done() && state.stopped_after.empty()) {
    if (paraview && next_dump >= 0 && sim.steps() >= next_dump) {
      paraview->write(sim);
      next_dump = (sim.steps() / dump_every + 1) * dump_every;
    }
    if (opt.stop_requested && opt.stop_requested()) {
      state.interrupted = true;
      break;
    }
    const long long budget = opt.stop_after > 0 ? opt.stop_after - (sim.steps() - first) : 1LL << 40;
    if (budget <= 0) break;
    const std::string stage = test.stage_name();
    const bool settling = stage == "settle";
    try {
      test.advance(std::min<long long>(budget, std::max(1LL, opt.chunk_steps)));
      sim.check();  // before frames, progress and checkpoints look at it
      if (settling && std::strcmp(test.stage_name(), "settle") != 0) report_packing(sim, dir, opt);
    } catch (const RunawayError& e) {
      // The simulation is at the step before the fault; the driver's state
      // is the one it had then (it only acts at readings, which are guarded).
      progress.end(test, sim.steps(), sim.time());
      save_fault(sim, dir, e, driver_state(test, wall_before + seconds_since(start)));
      out.save_rows(dir);
      throw;
    }
    if (opt.after_chunk) opt.after_chunk(sim, test);
    if (!opt.stop_at.empty() && stage == opt.stop_at && stage != test.stage_name()) {
      state.stopped_after = stage;
      break;
    }
    if (!announced && test.measuring()) {
      announced = true;
      if (!opt.quiet) out.on_measuring(opt.label);
    }
    progress.show(test, sim.steps(), sim.time());
    if (seconds_since(last_checkpoint) > opt.checkpoint_seconds) {
      save(sim, out, dir, wall_before + seconds_since(start));
      last_checkpoint = Clock::now();
    }
  }
  progress.end(test, sim.steps(), sim.time());
  state.wall_seconds = wall_before + seconds_since(start);
  save(sim, out, dir, state.wall_seconds);
  warn_late_builds(sim);
  state.finished = test.done();
  state.steps = sim.steps();
  state.particles = static_cast<int>(sim.scene().specimen_count());  // not a membrane's beads
  state.dt = sim.dt();
  if (state.finished) out.write_results(sim, dir, state.wall_seconds);
  // The state reached, finished or stopped, is the series' last frame: a
  // run stopped early (--stop-after, Ctrl-C) opens in ParaView too.
  if (paraview) paraview->write(sim);
  return state;
}

void save_fault(Simulation& sim, const fs::path& dir, const RunawayError& e,
                const std::string& extra) {
  const fs::path ck = dir / "fault_checkpoint.bin";
  save_checkpoint(sim, ck.string(), extra);
  write_file_atomic((dir / "fault.txt").string(),
                    std::string(e.what()) + "\nThe state at step " +
                        std::to_string(sim.steps()) + ", just before it, is in " + ck.string() +
                        "\n");
  std::fprintf(stderr, "[run] the state just before the fault (step %lld) is saved in %s\n",
               static_cast<long long>(sim.steps()), ck.string().c_str());
}

std::string driver_state(const LoadingProgramme& programme, double wall_seconds) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s%.3f\n", kWallKey, wall_seconds);
  return programme.save_state() + buf;
}

double driver_wall_seconds(const std::string& state) {
  const size_t at = state.rfind(kWallKey);
  return at == std::string::npos ? 0 : std::atof(state.c_str() + at + std::strlen(kWallKey));
}

std::string where_programme_is(const Simulation& sim, const LoadingProgramme& programme) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "step %lld, t = %.6g s, ", static_cast<long long>(sim.steps()),
                sim.time());
  return buf + programme.status();
}

std::unique_ptr<Simulation> load_run_checkpoint(const ProgrammeRunOptions& opt,
                                                std::string* state) {
  const fs::path ck = fs::path(opt.out_dir) / "checkpoint.bin";
  if (!fs::exists(ck))
    throw SceneError("io", ck.string(), 0, "--resume", "no checkpoint to resume from");
  return load_checkpoint(opt.device, ck.string(), state);
}

void restore_programme(LoadingProgramme& programme, const std::string& state,
                       const std::string& out_dir) {
  try {
    programme.restore_state(state);
  } catch (const std::exception& e) {
    throw SceneError("bad_checkpoint", (fs::path(out_dir) / "checkpoint.bin").string(), 0,
                     "--resume", e.what());
  }
}

bool programme_finished(const std::string& out_dir) {
  return fs::exists(fs::path(out_dir) / "summary.txt");
}

std::string resume_hint(const std::string& out_dir) {
  return "resume with: simsols run --resume --out " + out_dir;
}

void start_run_folder(const Scene& scene, const std::string& out_dir) {
  const fs::path dir = out_dir;
  fs::create_directories(dir);
  fs::remove(dir / "summary.txt");
  write_file_atomic((dir / "scene.toml").string(),
                    scene.source_text.empty() ? to_toml(scene) : scene.source_text);
  write_file_atomic((dir / "scene.resolved.toml").string(), to_toml(scene));
  write_grading_files(scene, out_dir);
}

}  // namespace simsols
