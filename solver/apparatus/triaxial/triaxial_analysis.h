// Triaxial analysis: a triaxial test's measurements and what is read from
// them (docs/triaxial.md), apart from the apparatus that measured them.
//
// Signs: compression positive, as in soil mechanics. Axial strain
// eps_a = (H0 - H) / H0, volumetric strain eps_v = (V0 - V) / V0 from the
// plates' positions (V = L W H), both from the end of consolidation.
//   p' = (s_x + s_y + s_z) / 3,
//   q  = sqrt(((s_x - s_y)^2 + (s_y - s_z)^2 + (s_z - s_x)^2) / 2)
//        (= s_1 - s_3 in the conventional test);
//   mobilised friction angle from Mohr's circle of the largest and
//        smallest principal stresses: sin(phi) = (s_1 - s_3) / (s_1 + s_3)
//        (= 3 eta / (6 + eta) in triaxial compression, eta = q / p');
//   dilatancy angle: sin(psi) = -r / (2 - r), r = d eps_v / d eps_a, the
//        slope over a window of 1 % axial strain (negative r: dilation).
// The peak is the largest running median of the mobilised angle over a
// window of kPeakWindow of axial strain (q/p', q, p', s_1, s_3 at the peak
// are their medians over the same window): a jamming event shorter than
// half the window, a column of beads locking for a moment, raises the
// largest angle (reported beside the peak, max_angle) but not the peak.
// The critical state is the mean over the last 20 % of the axial strain. Its Mohr circle spans the largest and
// smallest principal stresses, s_1 and s_3 (the largest and smallest plate
// stress).
//
// Over several tests (a campaign over sigma_3):
//   the Mohr-Coulomb envelope tangent to the circles, tau = c + sigma tan(phi):
//        the least-squares line t = a + s b through the circles' tops
//        (s = (s_1 + s_3) / 2, t = (s_1 - s_3) / 2), sin(phi) = b,
//        c = a / cos(phi);
//   the critical state line e = Gamma - lambda ln(p' / 1 kPa), least squares
//        over the tests' critical states.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/apparatus/shear_box/shear_analysis.h"

namespace simsols {

constexpr double kPeakWindow = 0.01;  // axial strain

struct TriaxialRow {
  double time = 0;               // s
  std::int64_t step = 0;
  double axial_strain = 0;       // compression positive
  double volumetric_strain = 0;  // compression positive
  // Pa, the plates' mean stresses; in a membrane the sides' are the cell
  // pressure and the hoop share, sigma_z the platen's less membrane_axial
  double sigma_x = 0, sigma_y = 0, sigma_z = 0;
  double p = 0, q = 0;           // Pa
  double friction_angle = 0;     // deg, mobilised
  double void_ratio = 0;
  double coordination = 0;       // contacts per bead (bead and wall contacts)
  double lw_x = 0, lw_y = 0, lw_z = 0;  // Pa, the Love-Weber stress of the whole cell
  // The largest difference between the plates' stresses at the row's last
  // step and lw_*, over the three axes, as a fraction of p' (the means
  // sigma_* span the whole row; the comparison is at one instant).
  double lw_gap = 0;
  double fabric_anisotropy = 0;  // (15/2)(phi_zz - (phi_xx + phi_yy)/2), phi = <n n> over bead pairs
  double kinetic_energy = 0;     // J
  double inertial_number = 0;    // strain_rate d sqrt(rho / p')
  // cell = "membrane": the membrane's share of the platen's stress, as
  // measured (subtracted from sigma_z) and as the shell estimate of
  // practice would give it (Pa; membrane_cell.h); 0 in the rigid cell
  double membrane_axial = 0, membrane_shell = 0;
};

struct TriaxialSummary {
  double confining_stress = 0;      // Pa
  double strain_rate = 0;           // 1/s
  double bead_diameter = 0;         // m
  double initial_void_ratio = 0;    // e after consolidation
  double peak_angle = 0, peak_q_over_p = 0, peak_axial_strain = 0, peak_q = 0, peak_p = 0;
  double peak_sigma1 = 0, peak_sigma3 = 0;  // Pa, the peak's Mohr circle
  double max_angle = 0, max_axial_strain = 0;  // the largest mobilised angle of any row
  double critical_angle = 0, critical_q_over_p = 0, critical_void_ratio = 0, critical_p = 0;
  double critical_sigma1 = 0, critical_sigma3 = 0;  // Pa, means over the critical rows
  double max_dilatancy_angle = 0;   // deg
  // The largest disagreement between the plates' stresses and the internal
  // (Love-Weber) stress at the same step, on any axis over the rows, as a
  // fraction of p' (TriaxialRow::lw_gap).
  double wall_internal_gap = 0;
  double median_wall_internal_gap = 0;  // the median over the rows
  double max_inertial_number = 0;
  // cell = "membrane": its hoop tension's share of the lateral stress at a
  // row, the largest in size (Pa, signed: negative where the membrane is
  // compressed; membrane_cell.h), which sigma_x and sigma_y include
  bool membrane = false;
  double max_membrane_stress = 0;
  // the last row's membrane_axial and membrane_shell (Pa)
  double end_membrane_axial = 0, end_membrane_shell = 0;
  double settle_time = 0, consolidate_time = 0;  // s
  double wall_seconds = 0;          // filled in by the caller
};

void analyse_triaxial_rows(const std::vector<TriaxialRow>& rows, TriaxialSummary& s);

// The mobilised friction angle (deg) of a stress state.
double mobilised_friction_angle(double sx, double sy, double sz);

std::string triaxial_rows_csv(const std::vector<TriaxialRow>& rows);
std::string triaxial_summary_text(const TriaxialSummary& s);
// triaxial.csv read back (a campaign keeping a finished test); throws
// std::runtime_error naming the row or column that is wrong.
std::vector<TriaxialRow> parse_triaxial_rows_csv(const std::string& text);

// The envelope tangent to Mohr circles (s_1, s_3 in Pa), as a Mohr-Coulomb
// line: cohesion (Pa), phi and their standard errors (see above).
MohrCoulomb fit_mohr_circles(const std::vector<double>& sigma1, const std::vector<double>& sigma3);

struct CriticalStateLine {
  double gamma = 0, lambda = 0;  // e = gamma - lambda ln(p' / 1 kPa)
  double lambda_se = 0;          // NaN with two points
  double r2 = 0;
  int points = 0;
};
CriticalStateLine fit_critical_state_line(const std::vector<double>& p, const std::vector<double>& e);

}  // namespace simsols
