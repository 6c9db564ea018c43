// What every laboratory test is, whatever its apparatus.
//
// A test is an apparatus operated by a loading programme:
//   apparatus     rigid walls and a specimen, built from the scene's
//                 description like a generator builds particles
//                 (build_shear_box: twelve rectangle walls and the beads);
//   stage         a named phase of the programme with an end condition:
//                 settle (kinetic energy died down), consolidate (the
//                 target stress held in equilibrium), shear (a displacement
//                 reached), and for the next apparatus isotropic
//                 compression, axial compression, a load step;
//   servo wall    a wall whose velocity a controller sets from its reaction
//                 to hold a target force (scene.h WallServo, switched and
//                 retargeted through Simulation::set_servo / read_servo),
//                 or a dead weight; a strain-controlled wall simply moves
//                 (Simulation::set_wall_velocity);
//   measurement   one row of named quantities with units, each a mean over
//                 the steps since the previous row (Simulation::
//                 read_wall_means), never a one-step sample; the rows are
//                 the test's result (shear_analysis.h reads them).
// The programme talks to the Simulation only through its run-time
// controls and readings; the physics stays in the pipeline. Its state is a
// few numbers and the rows, saved with the checkpoint, so an interrupted
// test resumes exactly.
//
// LoadingProgramme is the interface the drivers share (the headless run,
// the campaign, the lab, progress lines); ApparatusProgramme adds what a run
// writes of it (its rows file, summary.txt). ShearProgramme, OedometerProgramme and
// TriaxialProgramme implement it; the registry (registry.h) makes the one a
// scene's apparatus needs, so no driver names an apparatus.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

namespace simsols {

class LoadingProgramme {
 public:
  virtual ~LoadingProgramme() = default;

  // Runs at most `max_steps` steps, stopping early at a stage change or a
  // new row; returns true when a new row was measured.
  virtual bool advance(std::int64_t max_steps) = 0;
  virtual bool done() const = 0;
  // The current stage's name ("settle", "consolidate", "shear", "load", "done").
  virtual const char* stage_name() const = 0;
  // True once the stage the test is about has begun (shear, load): what
  // frames measure displacements from.
  virtual bool measuring() const = 0;

  // Steps of the whole programme: done so far, and done plus an estimate
  // of those left (exact once the last stage has begun).
  struct StepCount {
    double done = 0, total = 0;
  };
  virtual StepCount step_count() const = 0;
  double progress() const {
    const StepCount c = step_count();
    return c.total > 0 ? std::min(1.0, c.done / c.total) : 0;
  }
  // A one-line description of where the test is, for progress lines.
  virtual std::string status() const = 0;
  // What a picture of the test says of its state, with the symbols of the
  // plots: "δ = 2.62 mm, τ/σ = 0.157, σ = 160 kPa" (UTF-8).
  virtual std::string caption() const = 0;

  // The programme's own state (not the Simulation's), for checkpoints.
  virtual std::string save_state() const = 0;
  // Throws std::runtime_error when `text` is malformed.
  virtual void restore_state(const std::string& text) = 0;
};

// A loading programme that is an apparatus' test: what a headless run
// writes of it, whatever the apparatus.
class ApparatusProgramme : public LoadingProgramme {
 public:
  // The rows file's name in a run's folder ("shear.csv"), the rows so far
  // as CSV with units, and how many there are.
  virtual const char* rows_file() const = 0;
  virtual std::string rows_csv() const = 0;
  virtual std::size_t row_count() const = 0;
  // summary.txt of the test so far, with the wall seconds spent on it.
  virtual std::string summary_text(double wall_seconds) const = 0;
  // How the test is driven, for the run's header ("servo gain ... m/(s N),
  // integral time ... s").
  virtual std::string describe() const = 0;
  // A line for when the measured stage begins ("shearing at ... mm/s"), or "".
  virtual std::string measuring_line() const { return {}; }
};

}  // namespace simsols
