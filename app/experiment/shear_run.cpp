#include "app/experiment/shear_run.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <filesystem>

#include "solver/io/checkpoint.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "app/experiment/progress.h"
#include "app/experiment/run_cost.h"
#include "solver/io/scene_toml.h"
#include "app/experiment/shear_plots.h"
#include "solver/core/simulation.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

void save(Simulation& sim, const ShearTest& test, const fs::path& dir, double wall) {
  write_file_atomic((dir / "shear.csv").string(), shear_rows_csv(test.rows()));
  save_checkpoint(sim, (dir / "checkpoint.bin").string(), shear_driver_state(test, wall));
}

void print_header(const ShearRunOptions& opt, Simulation& sim, const ShearTest& test) {
  if (opt.quiet) return;
  const Scene& scene = sim.scene();
  std::fprintf(stderr,
               "[%s] %s: %d beads, dt = %.4g s (%.3g x Rayleigh), %s on %s; servo gain %.3g "
               "m/(s N), integral time %.3g s\n",
               opt.label.c_str(), scene.name.c_str(), sim.model().particles(), sim.dt(),
               sim.dt() / sim.model().rayleigh_dt(),
               sim.model().config().double_precision ? "double" : "float",
               sim.model().device().description().c_str(), test.servo_gain(),
               test.servo_integral_time());
  const LoadingProgramme::StepCount c = test.step_count();
  print_cost(opt.label, run_cost(sim, c.total - c.done));
}

void announce_shear(const ShearRunOptions& opt, const ShearTest& test) {
  if (opt.quiet) return;
  std::fprintf(stderr,
               "%s[%s] shearing at %.4g mm/s (inertial number %.2g at the start; target "
               "< 1e-3), specimen height %.2f mm\n",
               isatty(fileno(stderr)) ? "\r" : "", opt.label.c_str(), test.shear_speed() * 1e3,
               test.inertial_number(), test.summary().specimen_height * 1e3);
}

// Steps the test chunk by chunk until it is done, stopped (stop_after) or
// interrupted; checkpoints every checkpoint_seconds of wall time.
ShearRunResult drive(Simulation& sim, ShearTest& test, const ShearRunOptions& opt,
                     double wall_before) {
  const fs::path dir = opt.out_dir;
  print_header(opt, sim, test);
  ProgrammeProgress progress(opt.label, opt.quiet, opt.later_particle_steps,
                             sim.model().particles());
  progress.start(test);
  const auto start = Clock::now();
  auto last_checkpoint = start;
  const long long first = sim.steps();
  bool announced = test.phase() == ShearPhase::Shear;
  ShearRunResult result;
  while (!test.done()) {
    if (opt.stop_requested && opt.stop_requested()) {
      result.interrupted = true;
      break;
    }
    const long long budget = opt.stop_after > 0 ? opt.stop_after - (sim.steps() - first) : 1LL << 40;
    if (budget <= 0) break;
    try {
      test.advance(std::min<long long>(budget, std::max(1LL, opt.chunk_steps)));
      sim.check();  // before frames, progress and checkpoints look at it
    } catch (const RunawayError& e) {
      // The simulation is at the step before the fault; the driver's state
      // is the one it had then (it only acts at readings, which are guarded).
      progress.end(test, sim.steps(), sim.time());
      save_fault(sim, dir, e, shear_driver_state(test, wall_before + seconds_since(start)));
      write_file_atomic((dir / "shear.csv").string(), shear_rows_csv(test.rows()));
      throw;
    }
    if (opt.after_chunk) opt.after_chunk(sim, test.phase() == ShearPhase::Shear);
    if (!announced && test.phase() == ShearPhase::Shear) {
      announced = true;
      announce_shear(opt, test);
    }
    progress.show(test, sim.steps(), sim.time());
    if (seconds_since(last_checkpoint) > opt.checkpoint_seconds) {
      save(sim, test, dir, wall_before + seconds_since(start));
      last_checkpoint = Clock::now();
    }
  }
  progress.end(test, sim.steps(), sim.time());
  save(sim, test, dir, wall_before + seconds_since(start));
  if (sim.state().late_builds > 0)
    std::fprintf(stderr,
                 "warning: %lld neighbour-list checks found a bead beyond skin/2 (contacts may "
                 "have been missed); raise numerics.skin or lower the time step\n",
                 static_cast<long long>(sim.state().late_builds));
  result.rows = test.rows();
  result.summary = test.summary();
  result.summary.wall_seconds = wall_before + seconds_since(start);
  result.finished = test.done();
  result.steps = sim.steps();
  result.particles = sim.model().particles();
  result.dt = sim.dt();
  if (result.finished) {
    write_particles_vtk((dir / "particles_final.vtk").string(), sim.snapshot(), sim.time());
    write_shear_plots(dir.string(), sim.scene().name, result.rows, result.summary);
    write_file_atomic((dir / "summary.txt").string(), shear_summary_text(result.summary));
  }
  return result;
}

}  // namespace

void save_fault(Simulation& sim, const std::filesystem::path& dir, const RunawayError& e,
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

namespace {
constexpr const char* kWallKey = "\nwall_seconds_so_far ";
}  // namespace

std::string shear_driver_state(const ShearTest& test, double wall_seconds) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s%.3f\n", kWallKey, wall_seconds);
  return test.save_state() + buf;
}

double driver_wall_seconds(const std::string& state) {
  const size_t at = state.rfind(kWallKey);
  return at == std::string::npos ? 0 : std::atof(state.c_str() + at + std::strlen(kWallKey));
}

std::string where_test_is(const Simulation& sim, const ShearTest& test) {
  const double dx = test.rows().empty() ? 0 : test.rows().back().displacement;
  char buf[160];
  std::snprintf(buf, sizeof buf, "step %lld, t = %.6g s, %s, dx = %.3f mm (%zu rows)",
                static_cast<long long>(sim.steps()), sim.time(), phase_name(test.phase()),
                dx * 1e3, test.rows().size());
  return buf;
}

bool shear_finished(const std::string& out_dir) {
  return fs::exists(fs::path(out_dir) / "summary.txt");
}

std::string resume_hint(const std::string& out_dir) {
  return "resume with: simsols run --resume --out " + out_dir;
}

ShearRunResult resume_shear(std::unique_ptr<Simulation> sim, const std::string& state,
                            const ShearRunOptions& opt) {
  const std::string ck = (fs::path(opt.out_dir) / "checkpoint.bin").string();
  if (!sim->scene().shear_box)
    throw SceneError("bad_checkpoint", ck, 0, "--resume", "the checkpoint is not a shear test");
  ShearTest test(*sim);
  const double wall_before = driver_wall_seconds(state);  // of earlier, interrupted invocations
  try {
    test.restore_state(state);
  } catch (const std::exception& e) {
    throw SceneError("bad_checkpoint", ck, 0, "--resume", e.what());
  }
  std::fprintf(stderr, "[%s] resumed at %s\n", opt.label.c_str(), where_test_is(*sim, test).c_str());
  return drive(*sim, test, opt, wall_before);
}

ShearRunResult run_shear(const Scene& scene_in, const ShearRunOptions& opt) {
  const fs::path dir = opt.out_dir;
  if (opt.resume) {
    const fs::path ck = dir / "checkpoint.bin";
    if (!fs::exists(ck))
      throw SceneError("io", ck.string(), 0, "--resume", "no checkpoint to resume from");
    std::string state;
    auto sim = load_checkpoint(opt.device, ck.string(), &state);
    return resume_shear(std::move(sim), state, opt);
  }
  Simulation sim(opt.device, scene_in);
  ShearTest test(sim);
  fs::create_directories(dir);
  fs::remove(dir / "summary.txt");
  write_file_atomic((dir / "scene.toml").string(),
                    scene_in.source_text.empty() ? to_toml(scene_in) : scene_in.source_text);
  write_file_atomic((dir / "scene.resolved.toml").string(), to_toml(scene_in));
  return drive(sim, test, opt, 0);
}

}  // namespace simsols
