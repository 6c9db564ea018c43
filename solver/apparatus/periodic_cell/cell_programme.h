// CellProgramme: the periodic cell's loading programme and measurements.
//
// A Simulation of a scene with a [periodic_cell] is the apparatus; the
// programme sets the cell's velocity gradient L between steps (periodic_box.h)
// and operates it in named stages:
//   compress  every normal stress servo-controlled to the pressure, with
//             the preparation friction, until the specimen holds it: three
//             checks in a row with every normal stress within 1 % of it and
//             the particles' kinetic energy below 1e-6 of the elastic scale
//             p V (or the particles' rattling at inertial number below 1e-4);
//   test      the materials' own friction; simple shear (L_xz = gamma_dot,
//             L_xx = L_yy = 0, sigma_zz servo-controlled), a triaxial path
//             (L_zz = -epsilon_dot, the lateral stresses servo-controlled to
//             sigma_3 or to keep p) or nothing more (isotropic);
//   done.
// The stress servo (each controlled normal component on its own) sets
//   L_aa = P + I,  P = beta (sigma_aa - target) / (M dt_c),
//   I += P / 10 (the integral part, which follows a steady dilatancy),
//   |I|, |L_aa| <= rate_max
// every control (kControlSteps steps, dt_c apart), with M the affine
// (Voigt) stiffness of the packing's Hertz contacts under isotropic strain,
// an upper bound of the stiffness each stress answers with, and beta = 1:
// a control corrects at most the error it measured; rate_max is the strain
// rate of compression_inertial_number. Stresses are Love-Weber
// averages over the cell (periodic_cell.h); a row is the mean of the
// controls since the previous one, every row_strain of the test's strain.
// The programme's own state is saved with the checkpoint.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/apparatus/apparatus.h"
#include "solver/apparatus/periodic_cell/cell_analysis.h"
#include "solver/apparatus/periodic_cell/periodic_cell.h"
#include "solver/core/simulation.h"

namespace simsols {

class CellProgramme : public ApparatusProgramme {
 public:
  enum class Stage : int { Compress = 0, Test = 1, Done = 2 };
  static constexpr int kControlSteps = 20;

  explicit CellProgramme(Simulation& sim);

  bool advance(std::int64_t max_steps) override;
  bool done() const override { return stage_ == Stage::Done; }
  const char* stage_name() const override;
  bool measuring() const override { return stage_ == Stage::Test; }
  StepCount step_count() const override;
  std::string status() const override;
  std::string caption() const override;
  std::string save_state() const override;
  void restore_state(const std::string& text) override;

  const char* rows_file() const override { return "cell.csv"; }
  std::string rows_csv() const override;
  std::size_t row_count() const override { return rows_.size(); }
  std::string summary_text(double wall_seconds) const override;
  std::string describe() const override;
  std::string measuring_line() const override;
  CellSummary summary() const;

  const std::vector<CellRow>& rows() const { return rows_; }
  Stage stage() const { return stage_; }
  double strain() const { return strain_; }
  double test_rate() const;  // 1/s, gamma_dot or epsilon_dot
  double servo_rate_max() const;  // 1/s, the strain rate of compression_inertial_number
  double end_strain() const;

 private:
  void control();                 // one control: measure, servo, maybe a row
  void servo(const CellMeasure& m, Mat3& grad);
  bool compressed(const CellMeasure& m);
  void start_test();
  void apply_friction();
  void add_row();
  double stiffness(const CellMeasure& m) const;  // M, Pa
  double target(int axis, const CellMeasure& m) const;
  bool oedometric() const { return cell_.test == PeriodicCell::Test::Oedometric; }
  double vertical_stress() const {
    return cell_.vertical_stress > 0 ? cell_.vertical_stress : 4 * cell_.pressure;
  }
  // Oedometric: the grid's gradient along z, and the turn at the largest
  // stress and the end back at `pressure`.
  void oedometric_control(const CellMeasure& m, Mat3& grad);

  Simulation& sim_;
  const PeriodicCell& cell_;
  double diameter_ = 0, density_ = 0, e_star_ = 0;
  Stage stage_ = Stage::Compress;
  double strain_ = 0, volumetric_ = 0, volume0_ = 0, next_row_ = 0;
  // The strain travelled in the test (|d strain| summed: rows come every
  // row_strain of it), and the oedometric test's unloading half.
  double travel_ = 0;
  bool unloading_ = false, finished_ = false;
  int quiet_ = 0, controls_ = 0;
  std::int64_t since_control_ = 0;  // steps since the last control
  std::int64_t compress_steps_ = 0;
  std::array<double, 3> integral_{};  // the servo's integral part per axis, 1/s
  CellRow sum_{};  // the controls' sums since the last row
  int summed_ = 0;
  std::vector<CellRow> rows_;
};

}  // namespace simsols
