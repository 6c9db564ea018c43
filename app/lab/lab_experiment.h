// LabExperiment: the direct shear test as an operator runs it on a bench,
// without any window: the desktop lab (lab_app.cpp) and its scripted tests
// drive this class, and only this class touches the solver.
//
// Stages, in order (stage()):
//   Empty      no scene chosen
//   Building   the specimen and kernels are being built (a background
//              thread: the window keeps drawing)
//   Prepared   the specimen sits in the box, nothing has run
//   Loading    the normal stress is being applied (settle, then consolidate
//              under the servo platen)
//   Loaded     consolidated; the servo holds the normal stress; waiting for
//              start_shear()
//   Shearing   the lower half moves; rows are measured
//   Done       the shear displacement is reached
// paused() is separate: Loading and Shearing only advance while running.
// Changing the target normal stress or the shear speed takes effect at once
// (the servo follows); precision and effects apply from the next prepare()
// (the kernels are rebuilt, in the background).
//
// A failed scene load leaves the current experiment as it was and returns
// the error text for the panel. Checkpoints hold the simulation and the
// test's state; loading one continues exactly as the saved run would have.
#pragma once

#include <atomic>
#include <future>
#include <memory>
#include <string>
#include <utility>

#include "solver/scene/scene.h"
#include "solver/apparatus/shear_test.h"
#include "solver/core/simulation.h"

namespace simsols {

enum class LabStage { Empty, Building, Prepared, Loading, Loaded, Shearing, Done };
const char* to_string(LabStage s);

class LabExperiment {
 public:
  explicit LabExperiment(std::shared_ptr<Device> device);
  ~LabExperiment();

  // Scene choice. Empty string on success, else the error (nothing changed).
  std::string load_preset(double d_mm, double s_kpa);
  std::string load_scene_file(const std::string& path);
  const Scene& scene() const { return scene_; }
  const std::string& scene_label() const { return label_; }

  // Applied at the next prepare().
  void set_precision(Precision p) { scene_.numerics.precision = p; }
  void set_effects(const Effects& e) { scene_.effects = e; }
  void set_dt_fraction(double f) {
    scene_.numerics.dt_fraction = f;
    scene_.numerics.dt = 0;
  }

  // Bench actions; each returns an error text or "" (e.g. "prepare first").
  std::string prepare();  // starts the build; poll() finishes it
  std::string apply_normal_stress();
  std::string start_shear();
  void pause() { running_ = false; }
  void resume() { running_ = true; }
  bool paused() const { return !running_; }
  std::string step();     // one measurement row (shearing) or 200 steps (loading)
  std::string reset();    // a fresh specimen (same as prepare)
  std::string set_normal_stress(double pascals);
  std::string set_shear_speed(double metres_per_second);

  // Finishes a background build when it is ready; call once per frame.
  // Returns a build error, if any.
  std::string poll();
  // Advances while running, for about `budget_seconds` of wall time.
  std::int64_t advance(double budget_seconds);
  // Pause exactly when the test has this many rows / the simulation this
  // many steps (0 = no such stop): scripted sessions stop at the same state
  // whatever the frame timing.
  void pause_at(std::size_t rows, std::int64_t step) {
    pause_rows_ = rows;
    pause_step_ = step;
  }
  double steps_per_second() const { return rate_; }

  LabStage stage() const;
  Simulation* simulation() { return sim_.get(); }
  ShearTest* test() { return test_.get(); }
  // A new simulation object appeared (prepare, reset, checkpoint load):
  // views must re-attach. Counts up.
  int generation() const { return generation_; }

  // A runaway stopped the run (paused at the step before it): its message,
  // once; empty when none.
  std::string take_fault() { return std::exchange(fault_, {}); }
  std::string save_checkpoint(const std::string& path);
  std::string load_checkpoint(const std::string& path);
  // shear.csv, summary.txt and the plots, as the campaign writes them.
  std::string export_results(const std::string& dir);

 private:
  void adopt(std::unique_ptr<Simulation> sim, const std::string& state);

  std::shared_ptr<Device> device_;
  Scene scene_;
  std::string label_;
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<ShearTest> test_;
  std::future<std::unique_ptr<Simulation>> building_;
  bool running_ = false, loading_started_ = false;
  std::string fault_;  // a runaway (guard.h), until taken by take_fault()
  double rate_ = 0;            // steps per second of wall time, measured
  std::int64_t chunk_ = 100;   // steps per advance call, adapted to the budget
  std::size_t pause_rows_ = 0;
  std::int64_t pause_step_ = 0;
  int generation_ = 0;
};

}  // namespace simsols
