// TriaxialProgramme: the triaxial test's loading programme and measurements.
//
// A Simulation of a scene with a [triaxial] is the apparatus; the test
// operates it in named stages:
//   settle       gravity only, the plates held, until the kinetic energy
//                has died down (or settle_time);
//   consolidate  the platen is lowered onto the specimen and the platen
//                and the four sides are servo-controlled to the confining
//                stress (each target force is the stress times the plate's
//                current area, renewed at every check) until equilibrium:
//                twice in a row 0.5 ms apart every plate's mean stress
//                within 1 % of its target and the beads' RMS speed below
//                1e-4 (H/d) sqrt(p/rho) (or consolidate_time); with
//                cell = "membrane" the plates then hand the specimen to
//                the membrane at the confining stress (membrane_cell.h),
//                step back, and the specimen consolidates again under it
//                (the platen's area the mean cross-section inside it) to
//                the same criterion, the sides left out of it;
//   compress     a first row at rest, then the platen moves down at the
//                strain rate (from the inertial number unless given) while
//                the sides hold the stress path's lateral stresses (on a
//                constant-p or true-triaxial path renewed every 0.5 ms from
//                the platen's stress); a row every axial_strain / rows until
//                axial_strain;
//   done.
// Rows are means over the steps since the previous row (triaxial_analysis.h),
// with the internal (Love-Weber) stress and the fabric sampled at the row.
// The programme's state is saved with the checkpoint.
//
// Operator controls (the lab, and tests that walk an isotropic path): the
// confining stress and the strain rate can be changed at any stage (a new
// confining stress restarts the equilibrium checks; while compressing it is
// the new sigma_3 of the path); with hold_when_consolidated() the test
// stays in consolidate, the servos holding the stress, until
// start_compression(). at_rest() reads the state the last equilibrium
// check saw, which an isotropic compression or an unload-reload loop
// records step by step.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/apparatus/apparatus.h"
#include "solver/apparatus/cell/platen_servo.h"
#include "solver/apparatus/triaxial/triaxial_analysis.h"
#include "solver/core/simulation.h"

namespace simsols {

class TriaxialProgramme : public ApparatusProgramme {
 public:
  enum class Stage : int { Settle = 0, Consolidate = 1, Compress = 2, Done = 3 };

  // `sim` must hold a scene with a triaxial cell; it is not owned.
  explicit TriaxialProgramme(Simulation& sim);

  bool advance(std::int64_t max_steps) override;
  bool done() const override { return stage_ == Stage::Done; }
  const char* stage_name() const override;
  bool measuring() const override { return stage_ == Stage::Compress; }
  StepCount step_count() const override;
  std::string status() const override;
  std::string caption() const override;
  std::string save_state() const override;
  void restore_state(const std::string& text) override;  // throws std::runtime_error

  // ApparatusProgramme: triaxial.csv and the summary (triaxial_analysis.h).
  const char* rows_file() const override { return "triaxial.csv"; }
  std::string rows_csv() const override;
  std::size_t row_count() const override { return rows_.size(); }
  std::string summary_text(double wall_seconds) const override;
  std::string describe() const override;

  Stage stage() const { return stage_; }
  const std::vector<TriaxialRow>& rows() const { return rows_; }

  // The operator's controls (see above).
  void set_confining_stress(double pascals);
  void set_strain_rate(double per_second);
  void hold_when_consolidated(bool hold) { hold_ = hold; }
  bool holding() const { return hold_; }
  // True once consolidate has ended at the current confining stress, as a
  // run ends it: its equilibrium criterion met, or consolidate_time spent
  // (under a membrane the beads' speed can swing about the criterion for
  // longer; docs/triaxial.md). It stays true while holding.
  bool consolidated_now() const {
    return stage_ == Stage::Consolidate && consolidated_ && wrapped() == membrane_;
  }
  // Leaves consolidate for compress; false when the test is not consolidating.
  bool start_compression();
  double confining_stress() const { return sigma3_; }
  // Pa, the plates' mean stresses (x, y, z) at the last equilibrium check.
  std::array<double, 3> checked_stress() const { return consolidated_stress_; }

  // The specimen at the last equilibrium check of consolidate.
  struct AtRest {
    std::array<double, 3> stress{};  // Pa, the plates' mean stresses
    double p = 0;                    // Pa
    double volume = 0;               // m^3, the cell's
    double void_ratio = 0;
    double bead_coordination = 0;    // bead-bead contacts per bead (pairs counted twice)
    double porosity = 0;
  };
  AtRest at_rest();
  TriaxialSummary summary() const;
  double strain_rate() const { return rate_; }
  double bead_diameter() const { return stats_.diameter; }

 private:
  struct Cell {
    double x0, x1, y0, y1, z0, z1;
    double lx() const { return x1 - x0; }
    double ly() const { return y1 - y0; }
    double lz() const { return z1 - z0; }
  };
  Cell cell();
  // The membrane (cell = "membrane") once it holds the specimen: the
  // volume inside it, its mean cross-section (volume / height) and the
  // radial stress its hoop tension adds to the cell pressure.
  struct Wrapped {
    double volume = 0, area = 0, hoop_stress = 0;
  };
  bool wrapped() const { return wrap_step_ >= 0; }
  Wrapped wrapped_shape(const Cell& c);
  void wrap_membrane(const Cell& c);  // the hand-over from the plates to the membrane
  void enter(Stage s);
  // The plates' targets (Pa) for the stage: x, y and z (z unused while
  // compressing).
  std::array<double, 3> targets(double sigma_z) const;
  // `shape`: the membrane's, when the caller has just read it (else read
  // here, only when the platen is set).
  void apply_servos(const std::array<double, 3>& stress, bool platen, const Wrapped* shape = nullptr);
  bool consolidated();
  // Pa, x y z: the plates' mean stresses since the last read, or with the
  // membrane the cell pressure plus its hoop share and the platen's.
  std::array<double, 3> wall_stresses(const Cell& c, const Wrapped* w = nullptr);
  // A row; `at_rest` gives the plates' stresses of the last consolidation
  // check (the row at rest), else they are the means since the last row.
  void measure_row(const std::array<double, 3>* at_rest = nullptr);
  std::int64_t check_every() const;
  bool follows_platen() const;  // the path's side targets depend on the platen's stress
  void follow_platen();

  Simulation& sim_;
  const Triaxial& tri_;
  bool membrane_ = false;  // cell = "membrane"
  bool consolidated_ = false;  // the last consolidation check ended it (not checkpointed: the next one decides)
  double max_hoop_stress_ = 0;  // Pa, the membrane's share of sigma_3 largest in size at a row (signed)
  std::int64_t wrap_step_ = -1;  // the step the membrane took over; -1: not (yet)
  SpecimenStats stats_;
  bool started_ = false;
  Stage stage_ = Stage::Settle;
  std::int64_t stage_start_ = 0, next_check_ = 0, next_row_ = 0, row_steps_ = 1;
  std::int64_t compress_steps_ = 0;
  int quiet_checks_ = 0;
  double rate_ = 0;                 // 1/s
  double sigma3_ = 0;               // Pa, the confining stress (the scene's until set)
  bool hold_ = false;
  double h0_ = 0, v0_ = 0;          // at the start of compression
  double last_sigma_z_ = 0;         // Pa, the platen's stress at the last row
  std::array<double, 3> consolidated_stress_{};  // Pa, at the last consolidation check
  double settle_seconds_ = 0, consolidate_seconds_ = 0;
  std::vector<TriaxialRow> rows_;
};

}  // namespace simsols
