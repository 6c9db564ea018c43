// LabExperiment: a laboratory test as an operator runs it on a bench,
// without any window: the desktop lab (lab_app.cpp) and its scripted tests
// drive this class, and only this class touches the solver. The apparatus
// (shear box, triaxial cell, oedometer) is the scene's; what differs
// between them is behind LabApparatus (lab_apparatus.h).
//
// Stages, in order (stage()):
//   Empty      no scene chosen
//   Building   the specimen and kernels are being built (a background
//              thread: the window keeps drawing)
//   Prepared   the specimen sits in the apparatus, nothing has run
//   Loading    the stress is being applied (settle, then consolidate: the
//              shear box's normal stress, the triaxial cell's sigma3; the
//              oedometer settles here once its programme has started)
//   Loaded     consolidated; the servos hold the stress; waiting for start()
//   Running    the measured stage: shearing, compressing, the load steps
//   Done       the test's end is reached
// paused() is separate: Loading and Running only advance while running.
// Changing a setting (stress, speed, strain rate) takes effect at once (the
// servos follow); precision and effects apply from the next prepare() (the
// kernels are rebuilt, in the background).
//
// A failed scene load leaves the current experiment as it was and returns
// the error text for the panel. Checkpoints hold the simulation and the
// test's state; loading one continues exactly as the saved run would have.
#pragma once

#include <atomic>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "app/lab/lab_apparatus.h"
#include "solver/core/simulation.h"
#include "solver/scene/scene.h"

namespace simsols {

class LabExperiment {
 public:
  explicit LabExperiment(std::shared_ptr<Device> device);
  ~LabExperiment();

  // Scene choice. Empty string on success, else the error (nothing changed).
  std::string load_preset(double d_mm, double s_kpa);      // a shear box of Table 1
  std::string load_default(const LabBench& bench);         // the built-in scene
  std::string load_scene_file(const std::string& path);    // any of the three
  const Scene& scene() const { return scene_; }
  const std::string& scene_label() const { return label_; }

  // Applied at the next prepare().
  void set_precision(Precision p) { scene_.numerics.precision = p; }
  void set_effects(const Effects& e) { scene_.effects = e; }
  void set_dt_fraction(double f) {
    scene_.numerics.dt_fraction = f;
    scene_.numerics.dt = 0;
  }
  // A run profile (run_profile.h) applied to the specimen at prepare(), on
  // top of the panel's settings; "paper" changes nothing.
  void set_profile(const std::string& name) { profile_ = name; }
  const std::string& profile() const { return profile_; }

  // Bench actions; each returns an error text or "" (e.g. "prepare first").
  // Starts the build in the background; poll() finishes it. A scene that
  // asks a preparation (a relative density, tamping, radius expansion:
  // solver/apparatus/specimen/preparation.h) is prepared first, as
  // `simsols run` prepares it, and stopped when the lab closes (its
  // density.csv and friends in preparation_dir()); the prepared scene is
  // then the one Reset builds again, without searching.
  std::string prepare();
  std::string apply_load();  // the stress: settle, consolidate, hold
  std::string start();       // the measured stage (shear, compression, load programme)
  void pause() { running_ = false; }
  void resume() { running_ = true; }
  bool paused() const { return !running_; }
  std::string step();     // one measurement row (running) or 200 steps (loading)
  std::string reset();    // a fresh specimen (same as prepare)
  // A calibration's values set on the scene's materials (the next
  // prepare's); the keys that name no material's field are listed in the
  // returned note (they are not set), "" when all were.
  std::string set_materials(const std::vector<std::pair<std::string, double>>& values);
  // A live setting by key (LabApparatus::settings), in its unit.
  std::string set(const std::string& key, double value);
  // The apparatus' build choices (LabApparatus::choices; none before the
  // first prepare) and one of them set on the next prepare's scene.
  std::vector<LabChoice> choices() const;
  std::string choose(const std::string& key, const std::string& option);

  // Finishes a background build when it is ready; call once per frame.
  // Returns a build error, if any.
  std::string poll();
  // Advances while running, for about `budget_seconds` of wall time, and
  // on while *keep_going holds (the lab's drawing, on another thread; the
  // last chunk may overrun it by a quarter of the budget).
  std::int64_t advance(double budget_seconds, const std::atomic<bool>* keep_going = nullptr);
  // Pause exactly when the test has this many rows / the simulation this
  // many steps / the test reaches this stage (0, nullopt = no such stop):
  // scripted sessions stop at the same state whatever the frame timing.
  void pause_at(std::size_t rows, std::int64_t step, std::optional<LabStage> stage = {}) {
    pause_rows_ = rows;
    pause_step_ = step;
    pause_stage_ = stage;
  }
  double steps_per_second() const { return rate_; }

  LabStage stage() const;
  std::string stage_text() const;  // in the apparatus' words (the preparation's last line while building)
  const std::string& preparation_dir() const { return preparation_dir_; }
  Simulation* simulation() { return sim_.get(); }
  LabApparatus* apparatus() { return app_.get(); }
  std::size_t rows() const { return app_ ? app_->rows() : 0; }
  // A new simulation object appeared (prepare, reset, checkpoint load):
  // views must re-attach. Counts up.
  int generation() const { return generation_; }

  // A runaway stopped the run (paused at the step before it): its message,
  // once; empty when none.
  std::string take_fault() { return std::exchange(fault_, {}); }
  std::string save_checkpoint(const std::string& path);
  std::string load_checkpoint(const std::string& path);
  // The rows (shear.csv, triaxial.csv, oedometer.csv), summary.txt and the
  // plots, as `simsols run` writes them.
  std::string export_results(const std::string& dir);

 private:
  std::string adopt_scene(Scene sc, const std::string& label, const std::string& source,
                          bool keep_effects);
  void adopt(std::unique_ptr<Simulation> sim, const std::string& state);
  bool should_pause() const;

  std::shared_ptr<Device> device_;
  Scene scene_;
  std::string label_;
  std::string profile_ = "paper";  // set_profile
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<LabApparatus> app_;
  // What the background build says (its preparation's lines) and whether
  // it prepared the specimen, shared with the build's thread.
  struct BuildNews {
    mutable std::mutex mutex;
    std::string line;
    bool prepared = false;
    std::atomic<bool> cancel{false};  // the lab closes: the preparation stops
  };
  std::future<std::unique_ptr<Simulation>> building_;
  std::shared_ptr<BuildNews> news_;
  std::string preparation_dir_;
  bool running_ = false, loading_started_ = false;
  std::string fault_;  // a runaway (guard.h), until taken by take_fault()
  double rate_ = 0;            // steps per second of wall time, measured
  std::int64_t chunk_ = 100;   // steps per advance call, adapted to the budget
  std::size_t pause_rows_ = 0;
  std::int64_t pause_step_ = 0;
  std::optional<LabStage> pause_stage_;
  int generation_ = 0;
};

}  // namespace simsols
