// OedometerProgramme: the oedometer's loading programme and measurements.
//
// A Simulation of a scene with an [oedometer] is the apparatus; the test
// operates it in named stages:
//   settle   gravity only, the platen held above the beads, until the
//            kinetic energy has died down (or settle_time has passed);
//   load     the platen is lowered onto the settled specimen and its servo
//            brings the vertical stress to each of load_steps in turn; a
//            step is held until the specimen is in equilibrium under it,
//            twice in a row 0.5 ms apart: the platen's mean reaction within
//            1 % of the target, the beads' RMS speed below
//            1e-4 (H/d) sqrt(sigma/rho) and the platen's below a tenth of
//            that (the speeds of a deformation at inertial number 1e-4 and
//            1e-5), or for step_time at most (the step is then marked as
//            not in equilibrium and the test as not valid);
//   done     the servo is switched off.
// A row (oedometer_analysis.h) is measured at every check while loading,
// the means over the steps since the previous one; the row that ends a step
// says how it ended. As for the shear test, the programme talks to the
// Simulation only through its run-time controls and readings, and its own
// state is saved with the checkpoint so an interrupted test resumes exactly.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/apparatus/apparatus.h"
#include "solver/apparatus/oedometer/oedometer_analysis.h"
#include "solver/apparatus/cell/platen_servo.h"
#include "solver/core/simulation.h"

namespace simsols {

// Equilibrium of a load step, as inertial numbers of the beads' and the
// platen's speeds (see above) and the reaction's error.
constexpr double kOedometerBeadsInertial = 1e-4;
constexpr double kOedometerPlatenInertial = 1e-5;
constexpr double kOedometerForceError = 0.01;

class OedometerProgramme : public ApparatusProgramme {
 public:
  enum class Stage : int { Settle = 0, Load = 1, Done = 2 };

  // `sim` must hold a scene with an oedometer; it is not owned.
  explicit OedometerProgramme(Simulation& sim);

  bool advance(std::int64_t max_steps) override;
  bool done() const override { return stage_ == Stage::Done; }
  const char* stage_name() const override;
  bool measuring() const override { return stage_ == Stage::Load; }
  StepCount step_count() const override;
  std::string status() const override;
  std::string caption() const override;
  std::string save_state() const override;
  void restore_state(const std::string& text) override;  // throws std::runtime_error

  // ApparatusProgramme: oedometer.csv and the summary (oedometer_analysis.h).
  const char* rows_file() const override { return "oedometer.csv"; }
  std::string rows_csv() const override;
  std::size_t row_count() const override { return rows_.size(); }
  std::string summary_text(double wall_seconds) const override;
  std::string describe() const override;

  Stage stage() const { return stage_; }
  int load_step() const { return step_; }  // 0-based index into load_steps
  // Equilibrium checks passed in a row in the current step (2 ends it).
  int equilibrium_checks() const { return quiet_checks_; }
  const std::vector<OedometerRow>& rows() const { return rows_; }
  OedometerSummary summary() const;
  double bead_diameter() const { return stats_.diameter; }
  double servo_gain() const { return servo_.gain; }
  double servo_integral_time() const { return servo_.integral_time; }

 private:
  void enter(Stage s);
  void start_step(int index);  // retargets and retunes the platen's servo
  bool step_ended();  // measures a row; true when the step is over
  bool quiet(const OedometerRow& row, const Observables& beads);
  OedometerRow measure_row(const Observables& beads);
  double height();
  double target() const { return oed_.load_steps[step_]; }

  Simulation& sim_;
  const Oedometer& oed_;
  SpecimenStats stats_;
  PlatenServo servo_;
  bool started_ = false;
  Stage stage_ = Stage::Settle;
  int step_ = 0;
  std::int64_t stage_start_ = 0, step_start_ = 0, next_check_ = 0;
  int quiet_checks_ = 0;
  double settle_seconds_ = 0;
  std::vector<OedometerRow> rows_;
};

}  // namespace simsols
