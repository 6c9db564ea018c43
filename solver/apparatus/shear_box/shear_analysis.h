// Shear analysis: a direct shear test's measurements and what is read
// from them, apart from the apparatus that measured them.
//
// ShearRow is one row of the test (means over the steps of the row);
// analyse_shear_rows() turns the rows into a ShearSummary with the
// definitions of geotechnical practice (the first peak of the curve once
// single-row spikes are filtered out, the residual at the critical state
// where the volume stops changing, Taylor's energy check for dynamic
// events, the shear plane's normal stress, the normal-stress band and the
// test's validity); fit_mohr_coulomb() fits an envelope over several
// tests (the campaign fits one per specimen, campaign_report.h). ShearProgramme
// (shear_programme.h) fills the rows, the campaign re-reads kept tests through
// the CSV and summary parsers, the lab draws the same marks live; the
// definitions live here once.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace simsols {

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
  double sigma_target = 0;       // Pa, the target during the row (0: the test's)
  // Pa, the normal stress on the shear plane: the platen's load less what
  // the upper half's four side plates carry by friction (more, when a
  // dilating specimen drags them up), (N + sum F_z of the beads on them) / A
  // (0 in rows written before it was recorded). The grains' own
  // weight above the plane is not counted (0.2 kPa in the paper's box).
  double sigma_plane = 0;
  // rad, the loading cap's tilt about y (+: its +x end up; ShearBox::cap);
  // 0 for a held cap and in rows written before it was recorded
  double cap_tilt = 0;
};

// A test whose normal stress leaves this band (a fraction of its target, in
// any row) is invalid: reported, but left out of envelopes, as a laboratory
// discards a test whose load was not held.
constexpr double kValidSigmaBand = 0.10;

// A shear is quasi-static while its inertial number I = (v/H) d sqrt(rho/sigma)
// stays below this (da Cruz et al. 2005: the rate-independent regime).
constexpr double kQuasiStaticInertialNumber = 1e-3;

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
  // The residual (critical-state) strength: mean tau and tau/sigma over
  // the critical-state window (critical_state_of) from residual_from on;
  // when the test never reached zero volume change, over the last 20 % of
  // the travel with critical_state false. residual_dilation_rate: dz/dx
  // over that window (least squares).
  double residual_tau = 0, residual_ratio = 0, residual_angle = 0;
  bool critical_state = false;
  double residual_from = 0, residual_dilation_rate = 0;
  double max_dilatancy_angle = 0;   // deg, steepest rise of dz/dx (smoothed)
  // Taylor's (1948) energy balance, tau/sigma = mu* + dz/dx with mu* >= 0
  // (taylor_check): the smallest mu* of the test's windows, where it was,
  // and how many separate stretches had mu* < 0 (the platen rose faster
  // than the shear work could lift it: a dynamic event, not quasi-static
  // shearing); max_dilatancy_dynamic when the steepest rise is one.
  double taylor_min = 0, taylor_min_displacement = 0;
  int dynamic_events = 0;
  bool max_dilatancy_dynamic = false;
  // The wall-friction correction (ShearRow::sigma_plane): the share of the
  // platen's load the upper half's walls carried, mean over the shear
  // (percent), and the peak and residual angles on the shear plane's
  // normal stress, atan(tau / sigma_plane), beside those on the applied
  // one (the laboratory's reading). NaN when the rows do not record it.
  double wall_load_percent = 0;
  double peak_angle_plane = 0, residual_angle_plane = 0;
  double max_inertial_number = 0;
  double sigma_min = 0, sigma_max = 0;  // Pa, band of the row means during shear
  // The same band as fractions of each row's target (sigma / target - 1)
  // and the RMS of that deviation; valid when the band is within
  // +-kValidSigmaBand.
  double sigma_band_lo = 0, sigma_band_hi = 0, sigma_rms = 0;
  bool valid = true;
  bool quasi_static = true;         // max_inertial_number < kQuasiStaticInertialNumber
  // The first row, at rest before the lower half moves (displacement 0):
  // the horizontal force the specimen already exerts between the halves.
  double start_tau = 0, start_ratio = 0;
  double platen_mass = 0;           // kg, the dead weight's platen (0: servo)
  // The upper half (ShearBox::upper_half): floating or held, and how far
  // it had risen at the last row (m; negative: it sank, at most the gap).
  bool upper_half_floating = false;
  double upper_half_rise = 0;
  // The loading cap (ShearBox::cap): free to tilt or held, and its largest
  // tilt over the rows (rad, signed: the row's tilt of largest magnitude).
  bool cap_tilting = false;
  double cap_tilt_max = 0;
  int max_outside = 0;
  double settle_time = 0, consolidate_time = 0;  // s spent in each phase
  double wall_seconds = 0;          // filled in by the caller
};

// The analysis of a test's rows, apart from the apparatus that measured
// them (shared by ShearProgramme::summary, the campaign's kept tests and the
// lab): fills the row-derived fields of `s` (peak, largest, residual,
// dilatancy, sigma band and validity, inertial number, beads outside, the
// start) using each row's sigma_target (s.normal_stress_target for rows
// without one). Rows whose sigma is below half the target (a platen that
// lost contact) count for no ratio.
void analyse_shear_rows(const std::vector<ShearRow>& rows, ShearSummary& s);

// The residual strength: mean tau and tau/sigma over the last 20 % of the
// displacement.
struct Residual {
  double tau = 0, ratio = 0;
};
Residual residual_of(const std::vector<ShearRow>& rows, double sigma_target);

// The critical state: the longest final stretch of the test, starting in
// the second half of its travel, over which the specimen shears at
// constant volume: the least-squares rate dz/dx over the stretch within
// kCriticalDilationRate of zero, and over each of its two halves within
// twice that (no dilation cancelled by a later contraction), the stretch
// at least max(kCriticalMinDiameters d, 10 % of the travel) long (a rate
// over less shear is one rearrangement's). When there is one, `reached`,
// and tau and tau/sigma are its means; otherwise they are residual_of's
// (the last 20 %). `rate` is dz/dx over the stretch read.
constexpr double kCriticalDilationRate = 0.02;  // tan psi: |psi| <= 1.15 deg
constexpr double kCriticalMinDiameters = 0.25;
struct CriticalState {
  bool reached = false;
  double from = 0;  // m, displacement where the window starts
  double tau = 0, ratio = 0, rate = 0;
};
CriticalState critical_state_of(const std::vector<ShearRow>& rows, double sigma_target, double d);

// Taylor's (1948) energy balance for direct shear: the shear work pays for
// friction and for lifting the normal load, tau dx = mu* sigma dx + sigma dz,
// so in quasi-static shearing mu* = tau/sigma - dz/dx >= 0. Read over
// sliding windows of the dilatancy's width (ShearSummary::
// max_dilatancy_angle) that start at `from` or later; a stretch of
// windows with mu* < 0 is a dynamic event (elastic or kinetic energy
// released, a collapse or a jump of a layer), counted once. The balance
// holds for plastic flow: analyse_shear_rows checks from where tau/sigma
// first reaches half its peak (before, the specimen's elastic thrust at
// rest is released, and tau/sigma may still be negative).
struct TaylorCheck {
  double min_mu = 0, at = 0;  // the smallest mu* and the displacement of its window
  int events = 0;
};
TaylorCheck taylor_check(const std::vector<ShearRow>& rows, double sigma_target, double from = 0);

// The first peak of a test's rows (ShearSummary::peak_*): the running
// maximum of tau/sigma at the first sustained softening, a fall of more
// than `softening` below it that does not regain it within `recovery` of
// shear (m); counted once that maximum has reached a quarter of the test's
// largest tau/sigma and the residual strength (before, the curve's wiggles
// about zero and the stick-slip teeth of a hardening curve are not a
// peak). The largest value when the curve never softens. A granular
// specimen's tau fluctuates with rearrangements at the scale of a grain:
// a dip regained within a quarter of a bead diameter of shear
// (kPeakRecoveryDiameters) is such a fluctuation, not the softening after
// the peak (docs/shear-box.md).
constexpr double kPeakRecoveryDiameters = 0.25;
struct FirstPeak {
  double ratio = 0, displacement = 0;
  double tau = 0;  // Pa, in that row
  int row = -1;    // its index in `rows`; -1 when there is none
};
FirstPeak first_peak(const std::vector<ShearRow>& rows, double sigma_target, double recovery,
                     double softening = 0.05);

// The rows with their outliers of tau/sigma replaced (the Hampel filter:
// a row whose tau/sigma lies more than kHampelThreshold robust standard
// deviations, 1.4826 x the median absolute deviation, from the median of
// a centred window of `window` of displacement (m) gets that median as its
// tau/sigma; the other rows are kept as they are). A peak is read on these
// (peak_of): a spike of one rearrangement, a row or two far above its
// neighbours, goes, while the curve's own maxima, plateaus and cusps keep
// their height.
constexpr double kHampelThreshold = 3;
std::vector<ShearRow> smoothed_rows(const std::vector<ShearRow>& rows, double window);
// The peak of a test (ShearSummary::peak_*): first_peak of the rows
// filtered over kPeakSmoothingDiameters bead diameters of shear (and at
// least seven rows), with a recovery of kPeakRecoveryDiameters. A granular
// specimen's tau carries spikes of single rearrangements; the strength a
// laboratory reads is the curve's, not a spike's.
constexpr double kPeakSmoothingDiameters = 0.05;
FirstPeak peak_of(const std::vector<ShearRow>& rows, double sigma_target, double d);

// The rows as CSV (mm, kPa, N, J) and back; the summary as "key = value"
// lines and back. The parsers throw ReadError (common/errors.h) on malformed text.
std::string shear_rows_csv(const std::vector<ShearRow>& rows);
std::vector<ShearRow> parse_shear_rows_csv(const std::string& text);
std::string shear_summary_text(const ShearSummary& s);
ShearSummary parse_shear_summary(const std::string& text);
// The "key = value" lines of a summary.txt (SimSols' or another code's), as
// they stand: what parse_shear_summary reads its fields from.
std::map<std::string, std::string> summary_keys(const std::string& text);

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
