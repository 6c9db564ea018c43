// A loading programme run headless into a folder: what every apparatus'
// run shares (progress lines, checkpoints on a wall-time cadence, Ctrl-C,
// --stop-after, runaway faults, frames), with what differs between them
// (the rows file, the results, the header line) asked of a
// ProgrammeOutputs. apparatus_run.h is its user, for every apparatus.
//
// A folder's summary.txt is written last: its presence means the test
// finished. checkpoint.bin holds the simulation and the programme's state
// (driver_state), so `simsols run --resume --out DIR` continues exactly.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "solver/apparatus/apparatus.h"
#include "solver/common/errors.h"
#include "solver/core/cl_device.h"
#include "solver/core/simulation.h"

namespace simsols {

struct ProgrammeRunOptions {
  std::shared_ptr<Device> device;  // where the test runs (required)
  std::string out_dir;
  std::string label;           // progress-line prefix
  bool resume = false;         // continue from out_dir/checkpoint.bin
  bool quiet = false;
  long long stop_after = 0;    // stop (checkpointed) after this many steps; 0 = no limit
  // Stop (checkpointed) at the end of the stage of this name (a
  // LoadingProgramme::stage_name: "consolidate" stops a shear test
  // consolidated, before it shears); "" = none.
  std::string stop_at;
  double checkpoint_seconds = 60;  // wall time between checkpoints
  // Called after every chunk of at most `chunk_steps` steps (frame export):
  // the simulation and the programme (whether its measured stage has begun,
  // its caption).
  std::function<void(Simulation&, const LoadingProgramme&)> after_chunk;
  long long chunk_steps = 2000;
  // Polled between chunks (Ctrl-C, interrupt.h): when it answers true the
  // run writes its checkpoint and rows and returns with `interrupted`.
  std::function<bool()> stop_requested;
  // Particle-steps of the work that follows this test (the rest of a
  // campaign), so the progress line's ETA covers the whole programme.
  double later_particle_steps = 0;
};

// One apparatus' part of a headless run.
class ProgrammeOutputs {
 public:
  virtual ~ProgrammeOutputs() = default;
  virtual LoadingProgramme& programme() = 0;
  // The rows file (written at every checkpoint and at a fault).
  virtual void save_rows(const std::filesystem::path& dir) = 0;
  // The header's apparatus part ("servo gain ..."), after the scene's.
  virtual std::string describe() = 0;
  // Once, when the measured stage begins (a line saying how it runs).
  virtual void on_measuring(const std::string& /*label*/) {}
  // The results of a finished test; summary.txt last.
  virtual void write_results(Simulation& sim, const std::filesystem::path& dir,
                             double wall_seconds) = 0;
};

struct ProgrammeRunState {
  bool finished = false;       // false: stopped by stop_after, stop_at or interrupted (resumable)
  std::string stopped_after;   // the stage whose end stopped the run (options.stop_at), or ""
  bool interrupted = false;    // stopped by stop_requested
  long long steps = 0;
  int particles = 0;
  double dt = 0;
  double wall_seconds = 0;     // over every invocation
};

// Steps the programme chunk by chunk until it is done, stopped or
// interrupted, writing what options and `outputs` say. Throws RunawayError
// after saving the fault (save_fault) and the rows.
ProgrammeRunState drive_programme(Simulation& sim, ProgrammeOutputs& outputs,
                                  const ProgrammeRunOptions& options, double wall_before);

// A programme's state for a checkpoint's `extra` (checkpoint.h): its
// save_state() and the wall seconds spent on it so far, summed over
// interrupted invocations; and that time back from such a state (0 when it
// has none).
std::string driver_state(const LoadingProgramme& programme, double wall_seconds);
double driver_wall_seconds(const std::string& state);

// Where a test stands: "step N, t = ... s, <status>".
std::string where_programme_is(const Simulation& sim, const LoadingProgramme& programme);

// The checkpoint of a run to resume in out_dir, with the driver state it
// carried; SceneError when there is none.
std::unique_ptr<Simulation> load_run_checkpoint(const ProgrammeRunOptions& options,
                                                std::string* state);
// The programme's state restored from `state`; SceneError naming the
// checkpoint when it is malformed.
void restore_programme(LoadingProgramme& programme, const std::string& state,
                       const std::string& out_dir);

// One line for a run that stopped (interrupted or --stop-after): where, and
// the command that resumes it.
std::string resume_hint(const std::string& out_dir);

// After a RunawayError: `sim` (at the step before the fault) into
// dir/fault_checkpoint.bin with the driver's `extra`, and the message into
// dir/fault.txt.
void save_fault(Simulation& sim, const std::filesystem::path& dir, const RunawayError& e,
                const std::string& extra = {});

// True when out_dir holds a finished test (its summary.txt).
bool programme_finished(const std::string& out_dir);

// Starts a new test's folder: the scene as given and as used; an old
// summary.txt removed.
void start_run_folder(const Scene& scene, const std::string& out_dir);

}  // namespace simsols
