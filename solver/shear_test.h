// ShearTest: the direct shear test's loading program and measurements.
//
// A Simulation of a scene with a [shear_box] is an apparatus; ShearTest
// operates it as a technician would, in three named phases:
//   Settle       gravity only, platen held above the beads, until the kinetic
//                energy has died down (or settle_time has passed);
//   Consolidate  the platen's servo brings the normal force to sigma x area
//                and holds it, until the reaction is within 1% of the target
//                and the beads are quiet (or consolidate_time has passed);
//   Shear        the lower half moves in +x at the shear speed while the
//                servo holds sigma; a row is measured every
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

#include "simulation.h"

namespace simsols {

enum class ShearPhase : int { Settle = 0, Consolidate = 1, Shear = 2, Done = 3 };
const char* phase_name(ShearPhase p);

struct ShearRow {
  double time = 0;               // s
  std::int64_t step = 0;
  double displacement = 0;       // m, of the lower half since shearing started
  double shear_force = 0;        // N, on the moving (lower) half, mean over the row
  double shear_force_upper = 0;  // N, held by the upper half and platen (check of inertia)
  double tau = 0;                // Pa, T / nominal area
  double tau_corrected = 0;      // Pa, T / corrected area
  double normal_force = 0;       // N, platen reaction, mean over the row
  double sigma = 0;              // Pa, N / nominal area
  double dilation = 0;           // m, platen rise since shearing started (up +)
  double friction_angle = 0;     // deg, atan(tau / sigma)
  double coordination = 0;       // contacts per bead (bead and wall contacts)
  double kinetic_energy = 0;     // J
  double inertial_number = 0;
  int outside = 0;               // bead centres outside the box (must stay 0)
};

struct ShearSummary {
  double normal_stress_target = 0;  // Pa
  double shear_speed = 0;           // m/s
  double specimen_height = 0;       // m, at the start of shearing
  double bead_diameter = 0;         // m, mean
  // The peak strength in the geotechnical sense (ASTM D3080's reading of a
  // tau-displacement curve): the first maximum of tau/sigma after which the
  // specimen softens (tau/sigma falls by more than 5 % of it); peak_tau is
  // tau in that row.
  double peak_tau = 0, peak_ratio = 0, peak_angle = 0, peak_displacement = 0;
  // The largest tau/sigma of the whole test (max_ratio, max_angle at
  // max_displacement) and the largest tau: in a layered specimen this can be
  // a late jamming event, reported beside the peak but never as it.
  double max_tau = 0, max_ratio = 0, max_angle = 0, max_displacement = 0;
  double residual_tau = 0, residual_ratio = 0, residual_angle = 0;  // mean over the last 20%
  double max_dilatancy_angle = 0;   // deg, steepest rise of dz/dx (smoothed)
  double max_inertial_number = 0;
  double sigma_min = 0, sigma_max = 0;  // Pa, band of the row means during shear
  int max_outside = 0;
  double settle_time = 0, consolidate_time = 0;  // s spent in each phase
  double wall_seconds = 0;          // filled in by the caller
};

class ShearTest {
 public:
  // `sim` must hold a scene with a shear box; it is not owned.
  explicit ShearTest(Simulation& sim);

  // Runs at most `max_steps` steps, stopping early at a phase change or a
  // new row; returns true when a new row was measured.
  bool advance(std::int64_t max_steps);
  bool done() const { return phase_ == ShearPhase::Done; }
  ShearPhase phase() const { return phase_; }

  const std::vector<ShearRow>& rows() const { return rows_; }
  ShearSummary summary() const;

  double shear_speed() const { return speed_; }
  // At the start of shearing, with the target stress (0 before).
  double inertial_number() const;
  double servo_gain() const { return gain_; }
  double servo_integral_time() const { return integral_time_; }
  // Steps of the whole loading programme (settle, consolidate, shear):
  // done so far, and done plus an estimate of those left (exact once the
  // shear has begun). progress() = done / total.
  struct StepCount {
    double done = 0, total = 0;
  };
  StepCount step_count() const;
  double progress() const;
  // A one-line description of where the test is, for progress lines.
  std::string status() const;

  // The target normal stress can change while shearing (the servo follows).
  void set_normal_stress(double pascals);
  double normal_stress() const { return sigma_target_; }

  // Bench control (the desktop lab): with a hold, the test stops after
  // consolidation with the servo holding the normal stress, until
  // start_shear(). ready_to_shear() tells that consolidation is done.
  void hold_before_shear(bool on) { hold_ = on; }
  bool ready_to_shear() const { return phase_ == ShearPhase::Consolidate && ready_; }
  void start_shear();
  // A new shear speed (m/s, > 0), now if shearing, else from the start of
  // shearing; the remaining displacement is shared among the remaining rows.
  void set_shear_speed(double metres_per_second);

  std::string save_state() const;
  void restore_state(const std::string& text);  // throws std::runtime_error when malformed

 private:
  void enter(ShearPhase p);
  void apply_servo(bool on);
  void tune_servo();  // gain_ and integral_time_ for sigma_target_ (automatic settings)
  void move_lower_half(double vx);  // the floor, lower sides and frame at vx along x
  bool settled();
  bool consolidated();
  void measure_row();
  std::int64_t steps_for(double seconds) const;
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
  double x0_ = 0, z0_ = 0, height0_ = 0, diameter_ = 0, density_ = 0, bead_mass_ = 0;
  double k_hertz_ = 0, specimen_mass_ = 0, layers_ = 1;  // for tune_servo
  double settle_seconds_ = 0, consolidate_seconds_ = 0;
  int quiet_checks_ = 0;
  bool hold_ = false, ready_ = false;
  double speed_override_ = 0;      // m/s from set_shear_speed; 0 = none
  std::vector<ShearRow> rows_;
};

// The analysis of a test's rows, apart from the apparatus that measured
// them (shared by ShearTest::summary, the campaign's kept tests and the
// lab): fills the row-derived fields of `s` (peak, largest, residual,
// dilatancy, sigma band, inertial number, beads outside) using
// s.normal_stress_target. Rows whose sigma is below half the target (a
// platen that lost contact) count for no ratio.
void analyse_shear_rows(const std::vector<ShearRow>& rows, ShearSummary& s);

// The residual strength: mean tau and tau/sigma over the last 20 % of the
// displacement.
struct Residual {
  double tau = 0, ratio = 0;
};
Residual residual_of(const std::vector<ShearRow>& rows, double sigma_target);

// The first peak of a test's rows (ShearSummary::peak_*): the first
// running maximum of tau/sigma followed by a fall of more than `softening`
// of it, once that maximum has reached a quarter of the test's largest
// tau/sigma and the residual strength (before, the curve's wiggles about
// zero and the stick-slip teeth of a hardening curve are not a peak); the
// largest value when the curve never softens.
struct FirstPeak {
  double ratio = 0, displacement = 0;
  int row = -1;  // its index in `rows`; -1 when there is none
};
FirstPeak first_peak(const std::vector<ShearRow>& rows, double sigma_target,
                     double softening = 0.05);

// The rows as CSV (mm, kPa, N, J) and back; the summary as "key = value"
// lines and back. The parsers throw std::runtime_error on malformed text.
std::string shear_rows_csv(const std::vector<ShearRow>& rows);
std::vector<ShearRow> parse_shear_rows_csv(const std::string& text);
std::string shear_summary_text(const ShearSummary& s);
ShearSummary parse_shear_summary(const std::string& text);

// Mohr-Coulomb envelope tau = c + sigma tan(phi) by least squares over
// (sigma, tau) points (Pa), with the coefficient of determination R^2 and,
// from three points on, the standard errors of c and tan(phi) (ordinary
// least squares: s^2 = SS_res / (n - 2), se(tan phi) = s / sqrt(Sxx),
// se(c) = s sqrt(1/n + mean(sigma)^2 / Sxx)) and of phi (se(tan phi) /
// (1 + tan^2 phi), in degrees). Two points give the exact line through
// them: no error estimate (the standard errors are NaN, `exact` is true).
struct MohrCoulomb {
  double cohesion = 0;   // Pa
  double tan_phi = 0;
  double phi_deg = 0;
  double r2 = 0;
  int points = 0;
  bool exact = false;    // two points: the line through them
  double cohesion_se = 0, tan_phi_se = 0, phi_se_deg = 0;  // NaN when exact
};
MohrCoulomb fit_mohr_coulomb(const std::vector<double>& sigma, const std::vector<double>& tau);

}  // namespace simsols
