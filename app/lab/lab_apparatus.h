// LabApparatus: what the lab needs of a test, whatever its apparatus, so
// LabExperiment, the panel and the scripts run every apparatus the same way.
// One implementation per apparatus, each in its own file, wrapping that
// apparatus' LoadingProgramme:
//   lab_shear_box.cpp   ShearProgramme: apply the normal stress, hold, shear
//   lab_triaxial.cpp    TriaxialProgramme: settle and consolidate to sigma3, hold,
//                       compress
//   lab_oedometer.cpp   OedometerProgramme: settle, then the load steps by itself
//   lab_periodic_cell.cpp  CellProgramme: compress, then the test, by itself
//
// The lab's stages (LabStage) are the bench's: Prepared (nothing run),
// Loading (the stress is being applied: settling, consolidating), Loaded
// (consolidated, the stress held, waiting for start), Running (the measured
// stage: shearing, compressing, the load steps), Done. An apparatus that
// has no separate loading (the oedometer) goes from Prepared to Loading at
// start.
//
// Settings are the operator's live controls (normal stress, shear speed,
// confining stress, strain rate), named by a key the scripts use, in the
// units the panel shows.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "app/lab/lab_plots.h"
#include "solver/apparatus/apparatus.h"
#include "solver/core/simulation.h"
#include "solver/scene/scene.h"

namespace simsols {

enum class LabStage { Empty, Building, Prepared, Loading, Loaded, Running, Done };
const char* to_string(LabStage s);  // the apparatus-neutral words

class LabApparatus;

// What the lab has for each kind of the registry (solver/apparatus/
// registry.h), in the registry's order: the panel's word, its bench, and
// its default scene (nullptr: the shear box's 6.35 mm / 160 kPa preset).
struct LabBench {
  const char* kind;        // the registry's name
  const char* panel_name;  // "shear box"
  std::unique_ptr<LabApparatus> (*make)(Simulation& sim);
  const char* (*default_scene_text)();
  const char* default_scene_name;
};
std::span<const LabBench> lab_benches();
// The bench's index for the scene's apparatus, or for a kind's name; -1
// when there is none.
int lab_bench_index(const Scene& scene);
int lab_bench_index(std::string_view kind);

// One live control: `key` for scripts (set_stress -> "stress"), the
// panel's label, its unit and current value in that unit.
struct LabSetting {
  std::string key, label, unit;
  double value = 0;
};

// One choice of how the apparatus is built (the triaxial's cell): `key`
// for scripts (choose cell membrane), the panel's label, the options and
// the one the scene has now. It changes the scene and applies when the
// specimen is prepared again.
struct LabChoice {
  std::string key, label;
  std::vector<std::string> options;
  int current = 0;
};

class LabApparatus {
 public:
  virtual ~LabApparatus() = default;

  virtual const char* kind() const = 0;  // the registry's name
  virtual LoadingProgramme& programme() = 0;

  // The stage; `started` is true once loading (or the programme) has begun.
  virtual LabStage stage(bool started) const = 0;
  // The stage in this apparatus' words ("shearing", "compressing").
  virtual const char* stage_text(LabStage s) const = 0;
  // True in Loaded: the stress is held and the run waits for start().
  virtual bool holding() const = 0;

  // The bench's two actions; the panel's button labels (nullptr: none).
  virtual const char* load_label() const = 0;
  virtual const char* start_label() const = 0;
  // Loading begins (from Prepared). Error text, or "".
  virtual std::string begin_loading() = 0;
  // The measured stage begins (from `stage`). Error text, or "".
  virtual std::string start(LabStage stage) = 0;

  virtual std::vector<LabSetting> settings() const = 0;
  // Sets a setting (value in its unit) on the running test and in `scene`
  // (for the next prepare). Error text naming the key and range, or "".
  virtual std::string set(const std::string& key, double value, Scene& scene) = 0;

  // The apparatus' build choices as `scene` (the next prepare's) has them.
  virtual std::vector<LabChoice> choices(const Scene&) const { return {}; }
  // Sets a choice on `scene` (not yet placed). Error text naming the key
  // and its options, or "".
  virtual std::string choose(const std::string& key, const std::string& option, Scene& scene);

  virtual std::size_t rows() const = 0;
  virtual double inertial_number() const = 0;  // of the last row, 0 before
  // Lines for the panel under the buttons (the load step, equilibrium, ...).
  virtual std::string progress_text() const = 0;
  // A warning for the status line (a shear no longer quasi-static), or "".
  virtual std::string warning() const { return {}; }
  // `key = value` lines for the script's `state` (apparatus, rows, ...).
  virtual std::string state_lines() = 0;
  virtual std::vector<LabPlot> live_plots() const = 0;
  // The rows file, summary.txt and the PNG plots, as `simsols run` writes
  // them (throws on I/O errors).
  virtual void export_results(const std::string& dir, const std::string& title) = 0;
};

// The apparatus of `sim`'s scene, its test built on `sim` (not owned) and
// set to hold when loaded. nullptr when the scene has none the lab runs.
std::unique_ptr<LabApparatus> make_lab_apparatus(Simulation& sim);
// The registry's names of the kinds the lab runs: "shear_box|oedometer|triaxial".
std::string lab_kind_names();
std::unique_ptr<LabApparatus> make_lab_shear_box(Simulation& sim);  // lab_shear_box.cpp
std::unique_ptr<LabApparatus> make_lab_triaxial(Simulation& sim);   // lab_triaxial.cpp
std::unique_ptr<LabApparatus> make_lab_oedometer(Simulation& sim);  // lab_oedometer.cpp
std::unique_ptr<LabApparatus> make_lab_periodic_cell(Simulation& sim);  // lab_periodic_cell.cpp

// The unknown-key message: "set_rate: the shear box has no 'rate'; its
// settings: stress (kPa), speed (mm/s)".
std::string unknown_setting(const LabApparatus& a, const std::string& key);

}  // namespace simsols
