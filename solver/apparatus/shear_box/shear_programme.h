// ShearProgramme: the direct shear test's loading program and measurements.
//
// A Simulation of a scene with a [shear_box] is an apparatus; ShearProgramme
// operates it as a technician would, in three named phases:
//   Settle       gravity only, platen held above the beads, until the kinetic
//                energy has died down (or settle_time has passed);
//   Consolidate  the platen's servo brings the normal force to sigma x area
//                and holds it; with a dead weight (ShearBox::loading) the
//                load is then handed to it; the phase ends in equilibrium:
//                twice in a row (0.5 ms apart) the reaction is within 1 % of
//                the target, the beads' RMS speed is below 10 % and the
//                platen's speed below 1 % of the shear speed (or
//                consolidate_time has passed);
//   Shear        a first row is measured at rest (displacement 0), then the
//                lower half moves in +x at the shear speed while the platen
//                holds sigma; a row is measured every
//                shear_displacement / rows until shear_displacement.
// The driver only talks to the Simulation's run-time controls (wall
// velocities, servo settings) and its readings; the physics stays in the
// pipeline. Its own state is a few numbers and the rows, saved with the
// checkpoint (save_state / restore_state), so an interrupted test resumes
// exactly.
//
// Measurements (ShearRow): forces are means over the steps of the row
// (kept on the device every step), not one-step samples: the shear force T
// is what the actuator pushes the lower half with (minus the x-force of the
// beads on the floor and the lower plates), N the platen's reaction.
// tau = T / A, sigma = N / A on the nominal area A = length x width (and
// tau on the corrected area (length - dx) width); dilation = rise of the
// platen since shearing started (positive up); the mobilised friction angle
// atan(tau / sigma); the inertial number I = (v / H) d sqrt(rho / sigma).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/apparatus/apparatus.h"
#include "solver/apparatus/cell/platen_servo.h"
#include "solver/apparatus/shear_box/shear_analysis.h"
#include "solver/core/simulation.h"

namespace simsols {

enum class ShearPhase : int { Settle = 0, Consolidate = 1, Shear = 2, Done = 3 };
const char* phase_name(ShearPhase p);

// The direct shear test's loading programme (apparatus.h).
class ShearProgramme : public ApparatusProgramme {
 public:
  // `sim` must hold a scene with a shear box; it is not owned.
  explicit ShearProgramme(Simulation& sim);

  // LoadingProgramme: the stages are the phases (settle, consolidate,
  // shear, done); a row is measured every shear_displacement / rows.
  bool advance(std::int64_t max_steps) override;
  bool done() const override { return phase_ == ShearPhase::Done; }
  const char* stage_name() const override { return phase_name(phase_); }
  bool measuring() const override { return phase_ == ShearPhase::Shear; }
  StepCount step_count() const override;
  std::string status() const override;
  std::string caption() const override;
  std::string save_state() const override;
  void restore_state(const std::string& text) override;  // throws std::runtime_error when malformed

  // ApparatusProgramme: shear.csv and the summary (shear_analysis.h).
  const char* rows_file() const override { return "shear.csv"; }
  std::string rows_csv() const override;
  std::size_t row_count() const override { return rows_.size(); }
  std::string summary_text(double wall_seconds) const override;
  std::string describe() const override;
  std::string measuring_line() const override;

  ShearPhase phase() const { return phase_; }

  const std::vector<ShearRow>& rows() const { return rows_; }
  ShearSummary summary() const;

  double shear_speed() const { return speed_; }
  // At the start of shearing, with the target stress (0 before).
  double inertial_number() const;
  double servo_gain() const { return gain_; }
  double servo_integral_time() const { return integral_time_; }

  // The target normal stress can change while shearing (the platen
  // follows). With an automatic shear speed (from the inertial number and
  // no set_shear_speed) the speed follows too, so the test stays as
  // quasi-static as it began: I = (v/H) d sqrt(rho/sigma) is held.
  void set_normal_stress(double pascals);
  // The dead weight's platen mass (kg), 0 with a servo.
  double platen_mass() const { return dead_weight() ? platen_mass_ : 0; }
  double normal_stress() const { return sigma_target_; }
  double bead_diameter() const { return diameter_; }  // m

  // Bench control (the desktop lab): with a hold, the test stops after
  // consolidation with the servo holding the normal stress, until
  // start_shear(). ready_to_shear() tells that consolidation is done.
  void hold_before_shear(bool on) { hold_ = on; }
  bool ready_to_shear() const { return phase_ == ShearPhase::Consolidate && ready_; }
  void start_shear();
  // A new shear speed (m/s, > 0), now if shearing, else from the start of
  // shearing; the remaining displacement is shared among the remaining rows.
  void set_shear_speed(double metres_per_second);


 private:
  bool dead_weight() const { return box_.loading == ShearBox::Loading::DeadWeight; }
  void enter(ShearPhase p);
  void apply_servo(bool on);
  void tune_servo();  // gain_ and integral_time_ for sigma_target_ (automatic settings)
  void move_lower_half(double vx);  // the floor, lower sides and frame at vx along x
  void float_upper_half(bool on);   // a floating upper half set free (on) or held
  double upper_half_rise() const;   // m the upper half has risen since the scene placed it
  bool settled();
  bool consolidated();
  bool equilibrium(double reaction);  // consolidated()'s criterion, with the dead weight's handover
  void measure_row();
  void retime_rows(double speed);  // the remaining rows at a new shear speed
  std::int64_t steps_for(double seconds) const;
  double specimen_height() const;  // m, platen to floor
  double shear_speed_for(double height) const;  // shear_speed, or from inertial_number

  Simulation& sim_;
  const ShearBox& box_;
  bool started_ = false;
  ShearPhase phase_ = ShearPhase::Settle;
  std::int64_t phase_start_ = 0;   // step the phase began
  std::int64_t next_check_ = 0;    // step of the next look at the phase's end condition
  std::int64_t next_row_ = 0;      // step of the next row (Shear)
  std::int64_t row_steps_ = 1;
  std::int64_t shear_steps_ = 0;   // steps the shear takes
  double sigma_target_ = 0;
  double speed_ = 0, gain_ = 0, integral_time_ = 0;
  SpecimenStats stats_;
  double x0_ = 0, z0_ = 0, height0_ = 0, diameter_ = 0, density_ = 0;
  double settle_seconds_ = 0, consolidate_seconds_ = 0;
  int quiet_checks_ = 0;
  bool hold_ = false, ready_ = false;
  bool loaded_ = false;            // the dead weight carries the load (else the servo)
  double platen_mass_ = 0;         // kg, for the dead weight
  double speed_override_ = 0;      // m/s from set_shear_speed; 0 = none
  std::vector<ShearRow> rows_;
};

}  // namespace simsols
