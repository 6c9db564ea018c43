// One direct shear test run headless into a folder, shared by `simsols run`
// (a scene with a [shear_box]) and `simsols campaign` (many of them).
//
// Folder layout:
//   scene.toml, scene.resolved.toml   the scene as given / as used (explicit beads)
//   shear.csv                         one row per measurement (see ShearRow)
//   summary.txt                       peak / residual / dilatancy / servo band
//   shear_stress.png, shear_ratio.png, dilation.png   the paper's Figures 3-7 axes
//   particles_final.vtk               the specimen at the end, for ParaView
//   checkpoint.bin                    latest state; `--resume` continues from it
//   fault.txt, fault_checkpoint.bin   only when a step ran away (guard.h): what,
//                                     where, and the state just before it
// summary.txt is written last: its presence means the test finished.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "solver/core/cl_device.h"
#include "solver/scene/scene.h"
#include "solver/apparatus/shear_test.h"

namespace simsols {

struct ShearRunOptions {
  std::shared_ptr<Device> device;  // where the test runs (required)
  std::string out_dir;
  std::string label;           // progress-line prefix
  bool resume = false;         // continue from out_dir/checkpoint.bin
  bool quiet = false;
  long long stop_after = 0;    // stop (checkpointed) after this many steps; 0 = no limit
  double checkpoint_seconds = 60;  // wall time between checkpoints
  // Called after every chunk of at most `chunk_steps` steps (frame export):
  // the simulation and whether the shear phase has begun.
  std::function<void(Simulation&, bool shearing)> after_chunk;
  long long chunk_steps = 2000;
  // Polled between chunks (Ctrl-C, interrupt.h): when it answers true the
  // run writes its checkpoint and rows and returns with `interrupted`.
  std::function<bool()> stop_requested;
  // Particle-steps of the work that follows this test (the rest of a
  // campaign), so the progress line's ETA covers the whole programme.
  double later_particle_steps = 0;
};

struct ShearRunResult {
  ShearSummary summary;
  std::vector<ShearRow> rows;
  bool finished = false;       // false: stopped by stop_after or interrupted (resumable)
  bool interrupted = false;    // stopped by stop_requested
  long long steps = 0;
  int particles = 0;
  double dt = 0;
};

// Runs (or resumes) the test of `scene` (ignored when resuming). Throws
// SceneError / DeviceError like the other commands, and RunawayError when a
// step ran away (after saving the state before it, see save_fault).
ShearRunResult run_shear(const Scene& scene, const ShearRunOptions& options);

// Continues the test in options.out_dir from a checkpoint already loaded
// (`sim`, with the driver state `extra` it carried); prints where it
// resumed ("resumed at step N, t = ..., dx = ... mm").
ShearRunResult resume_shear(std::unique_ptr<Simulation> sim, const std::string& extra,
                            const ShearRunOptions& options);

// A shear test's state for a checkpoint's `extra` (checkpoint.h): its
// loading programme (ShearTest::save_state) and the wall seconds spent on
// it so far, summed over interrupted invocations; and that time back from
// such a state (0 when it has none).
std::string shear_driver_state(const ShearTest& test, double wall_seconds);
double driver_wall_seconds(const std::string& state);

// Where a test stands: "step N, t = ... s, shear, dx = ... mm (R rows)".
std::string where_test_is(const Simulation& sim, const ShearTest& test);

// One line for a run that stopped (interrupted or --stop-after): where, and
// the command that resumes it.
std::string resume_hint(const std::string& out_dir);

// After a RunawayError: `sim` (at the step before the fault) into
// dir/fault_checkpoint.bin with the driver's `extra`, and the message into
// dir/fault.txt.
void save_fault(Simulation& sim, const std::filesystem::path& dir, const RunawayError& e,
                const std::string& extra = {});

// True when out_dir holds a finished test (its summary.txt).
bool shear_finished(const std::string& out_dir);

}  // namespace simsols
