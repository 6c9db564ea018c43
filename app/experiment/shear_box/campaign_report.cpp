#include "app/experiment/shear_box/campaign_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>

#include "app/experiment/shear_box/shear_plots.h"
#include "app/experiment/shear_box/study_stats.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

constexpr auto fmt = format_number;  // printf conversion of one number (output.h)

namespace fs = std::filesystem;

std::string csv_header() {
  return "diameter_mm,layers,normal_stress_kPa,seed,peak_tau_kPa,peak_tau_over_sigma,"
         "peak_friction_angle_deg,peak_displacement_mm,max_tau_over_sigma,"
         "max_friction_angle_deg,max_displacement_mm,residual_tau_kPa,"
         "residual_friction_angle_deg,critical_state,residual_from_mm,residual_dilation_rate,"
         "max_dilatancy_angle_deg,max_dilatancy_dynamic,dynamic_events,taylor_min_mu,"
         "wall_load_percent,peak_friction_angle_plane_deg,residual_friction_angle_plane_deg,"
         "max_inertial_number,sigma_band_min_percent,sigma_band_max_percent,sigma_rms_percent,"
         "valid,start_tau_over_sigma,beads,upper_half_rise_mm,cap_tilt_max_deg,steps,wall_seconds\n";
}

const char* yes_no(bool b) { return b ? "yes" : "no"; }

std::string csv_row(const CampaignEntry& e) {
  const ShearSummary& s = e.summary;
  std::ostringstream o;
  o << fmt("%g", e.d_mm) << ',' << e.layers << ',' << fmt("%g", e.s_kpa) << ',' << e.seed << ','
    << fmt("%.6g", s.peak_tau * 1e-3) << ',' << fmt("%.6g", s.peak_ratio) << ','
    << fmt("%.4f", s.peak_angle) << ',' << fmt("%.6g", s.peak_displacement * 1e3) << ','
    << fmt("%.6g", s.max_ratio) << ',' << fmt("%.4f", s.max_angle) << ','
    << fmt("%.6g", s.max_displacement * 1e3) << ',' << fmt("%.6g", s.residual_tau * 1e-3) << ','
    << fmt("%.4f", s.residual_angle) << ',' << yes_no(s.critical_state) << ','
    << fmt("%.6g", s.residual_from * 1e3) << ',' << fmt("%.4g", s.residual_dilation_rate) << ','
    << fmt("%.4f", s.max_dilatancy_angle) << ',' << yes_no(s.max_dilatancy_dynamic) << ','
    << s.dynamic_events << ',' << fmt("%.4g", s.taylor_min) << ','
    << fmt("%.3f", s.wall_load_percent) << ',' << fmt("%.4f", s.peak_angle_plane) << ','
    << fmt("%.4f", s.residual_angle_plane) << ','
    << fmt("%.4g", s.max_inertial_number) << ',' << fmt("%.3f", 100 * s.sigma_band_lo) << ','
    << fmt("%.3f", 100 * s.sigma_band_hi) << ',' << fmt("%.3f", 100 * s.sigma_rms) << ','
    << yes_no(s.valid) << ',' << fmt("%.4f", s.start_ratio) << ',' << e.beads << ','
    << fmt("%.4g", s.upper_half_rise * 1e3) << ',' << fmt("%.4g", s.cap_tilt_max * 180 / std::numbers::pi)
    << ',' << (e.rows.empty() ? 0 : e.rows.back().step)
    << ',' << fmt("%.1f", s.wall_seconds) << '\n';  // the wall time last (tests drop it)
  return o.str();
}

std::string md_row(const CampaignEntry& e) {
  const ShearSummary& s = e.summary;
  std::ostringstream o;
  o << "| " << fmt("%g", e.d_mm) << " | " << fmt("%g", e.s_kpa) << " | " << e.seed << " | "
    << fmt("%.1f", s.peak_tau * 1e-3) << " | " << fmt("%.2f", s.peak_angle) << " at "
    << fmt("%.2f", s.peak_displacement * 1e3) << " mm | " << fmt("%.2f", s.max_angle) << " | "
    << fmt("%.2f", s.residual_angle)
    << (s.critical_state ? " from " + fmt("%.1f", s.residual_from * 1e3) + " mm"
                         : std::string(" (not reached)"))
    << " | " << fmt("%.2f", s.max_dilatancy_angle) << (s.max_dilatancy_dynamic ? " (dynamic)" : "")
    << " | " << s.dynamic_events << " | " << fmt("%+.2f", 100 * s.sigma_band_lo) << " / "
    << fmt("%+.2f", 100 * s.sigma_band_hi) << (s.valid ? "" : " **invalid**") << " | "
    << fmt("%.3f", s.start_ratio) << " | " << fmt("%.2g", s.max_inertial_number) << " | "
    << fmt("%.0f", s.wall_seconds) << " |\n";
  return o.str();
}

// "12.34 ± 0.56" (half width or standard error), or the value alone.
std::string pm(double value, double spread, const char* f) {
  return fmt(f, value) + (std::isfinite(spread) ? " ± " + fmt(f, spread) : "");
}

// One size and stress over its specimens.
std::string ensemble_row(double d, double s_kpa, const std::vector<const CampaignEntry*>& tests,
                         std::string& md) {
  std::vector<double> peak, residual, peak_tau, res_tau, psi, res_plane, wall_load;
  int critical = 0, dynamic = 0;
  for (const CampaignEntry* t : tests) {
    peak.push_back(t->summary.peak_angle);
    residual.push_back(t->summary.residual_angle);
    peak_tau.push_back(t->summary.peak_tau * 1e-3);
    res_tau.push_back(t->summary.residual_tau * 1e-3);
    psi.push_back(t->summary.max_dilatancy_angle);
    res_plane.push_back(t->summary.residual_angle_plane);
    wall_load.push_back(t->summary.wall_load_percent);
    critical += t->summary.critical_state;
    dynamic += t->summary.dynamic_events > 0;
  }
  std::ostringstream o;
  o << fmt("%g", d) << ',' << fmt("%g", s_kpa) << ',' << tests.size();
  std::vector<Interval> in;  // in the CSV's order: peak, residual, ..., psi (4)
  for (const auto* x : {&peak, &residual, &peak_tau, &res_tau, &psi, &res_plane, &wall_load}) {
    in.push_back(mean_ci95(*x));
    o << ',' << fmt("%.6f", in.back().mean) << ',' << fmt("%.6f", in.back().half_width);
  }
  o << ',' << critical << ',' << dynamic << '\n';
  md += "| " + fmt("%g", d) + " | " + fmt("%g", s_kpa) + " | " + std::to_string(tests.size()) +
        " | " + pm(in[0].mean, in[0].half_width, "%.2f") + " | " +
        pm(in[1].mean, in[1].half_width, "%.2f") + " | " + pm(in[4].mean, in[4].half_width, "%.1f") +
        " | " + std::to_string(critical) + " | " + std::to_string(dynamic) + " |\n";
  return o.str();
}

// One size's envelope of one strength: the table rows, the plot series.
struct Envelope {
  std::string csv_row, table_row;
  EnvelopeSeries series;
  bool fitted = false;
};

// Each specimen's fit over its stresses (two or more valid tests).
std::vector<MohrCoulomb> specimen_fits(const std::vector<const CampaignEntry*>& tests,
                                       bool residual, EnvelopeSeries& series) {
  std::map<std::int64_t, std::pair<std::vector<double>, std::vector<double>>> by_seed;
  for (const CampaignEntry* t : tests) {
    const double tau = residual ? t->summary.residual_tau : t->summary.peak_tau;
    by_seed[t->seed].first.push_back(t->summary.normal_stress_target);
    by_seed[t->seed].second.push_back(tau);
    series.sigma.push_back(t->summary.normal_stress_target);
    series.tau.push_back(tau);
  }
  std::vector<MohrCoulomb> fits;
  for (const auto& [seed, pts] : by_seed)
    if (pts.first.size() >= 2) fits.push_back(fit_mohr_coulomb(pts.first, pts.second));
  return fits;
}

Envelope fit_envelope(double d_mm, const std::vector<const CampaignEntry*>& tests, bool residual) {
  Envelope e;
  e.series.label = fmt("%g mm", d_mm);
  const std::string which = residual ? "residual" : "peak";
  const std::vector<MohrCoulomb> fits = specimen_fits(tests, residual, e.series);
  const std::string head = fmt("%g", d_mm) + "," + which + "," + std::to_string(fits.size());
  if (fits.empty()) {
    e.table_row = "| " + fmt("%g", d_mm) + " | " + which +
                  " | – | – | 0 | needs two or more stresses per specimen |\n";
    e.csv_row = head + ",,,,,\n";
    return e;
  }
  const SpecimensEnvelope env = specimens_envelope(fits);
  const double phi = env.phi_deg, phi_hw = env.phi_spread_deg, c = env.c_kpa, c_hw = env.c_spread_kpa;
  const std::string how =
      env.ci95() ? "mean of the specimens' fits ± 95 % interval; their mean R² = " + fmt("%.4f", env.mean_r2)
      : fits[0].exact
          ? "one specimen, two points: no error estimate"
          : "one specimen: ± one standard error of its fit, R² = " + fmt("%.4f", fits[0].r2);
  e.series.tan_phi = std::tan(phi * std::acos(-1.0) / 180);
  e.series.cohesion = c * 1e3;
  e.fitted = true;
  e.table_row = "| " + fmt("%g", d_mm) + " | " + which + " | " + pm(phi, phi_hw, "%.2f") + " | " +
                pm(c, c_hw, "%.2f") + " | " + std::to_string(fits.size()) + " | " + how + " |\n";
  e.csv_row = head + "," + fmt("%.6f", phi) + "," + fmt("%.6f", phi_hw) + "," + fmt("%.6f", c) +
              "," + fmt("%.6f", c_hw) + "," + (fits.size() > 1 ? "ci95" : "se") + "\n";
  std::printf("Mohr-Coulomb d = %g mm (%s): phi = %s deg, c = %s kPa (%zu specimen%s)\n", d_mm,
              which.c_str(), pm(phi, phi_hw, "%.2f").c_str(), pm(c, c_hw, "%.2f").c_str(),
              fits.size(), fits.size() > 1 ? "s, 95 % interval" : ", standard error");
  return e;
}

const char* kTestsIntro =
    "Peak: the first peak of τ/σ after single-row spikes are removed (a Hampel filter over "
    "d/20 of travel, docs/shear-box.md); largest: the "
    "largest τ/σ of a row; residual: the mean at the critical state, from where |dz/dx| stays "
    "below 0.02 to the end (\"not reached\": the last 20 % of the travel, while the volume still "
    "changes); ψ max: the steepest rise, \"(dynamic)\" when Taylor's energy balance could not "
    "pay for it; events: stretches where τ/σ − dz/dx < 0 (a dynamic event). σ band: the row "
    "means' deviation from the target; a test beyond ±10 % is invalid and left out of the "
    "envelopes.\n\n"
    "| d (mm) | σ (kPa) | seed | τ peak (kPa) | φ peak (°) | φ largest (°) | φ residual (°) | "
    "ψ max (°) | events | σ band (%) | τ/σ at rest | I max | wall (s) |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

}  // namespace

SpecimensEnvelope specimens_envelope(const std::vector<MohrCoulomb>& fits) {
  SpecimensEnvelope e;
  e.specimens = static_cast<int>(fits.size());
  if (fits.empty()) return e;
  if (fits.size() == 1) {
    const MohrCoulomb& f = fits[0];
    e.phi_deg = f.phi_deg;
    e.phi_spread_deg = f.phi_se_deg;
    e.c_kpa = f.cohesion * 1e-3;
    e.c_spread_kpa = f.cohesion_se * 1e-3;
    e.mean_r2 = f.r2;
    return e;
  }
  std::vector<double> phis, cs;
  for (const MohrCoulomb& f : fits) {
    phis.push_back(f.phi_deg);
    cs.push_back(f.cohesion * 1e-3);
    e.mean_r2 += f.r2 / static_cast<double>(fits.size());
  }
  const Interval ip = mean_ci95(phis), ic = mean_ci95(cs);
  e.phi_deg = ip.mean;
  e.phi_spread_deg = ip.half_width;
  e.c_kpa = ic.mean;
  e.c_spread_kpa = ic.half_width;
  return e;
}

std::string describe_fit(const MohrCoulomb& m) {
  char buf[200];
  if (m.exact)
    std::snprintf(buf, sizeof buf,
                  "phi = %.2f deg, c = %.2f kPa (2 points: the line through them, no error "
                  "estimate)",
                  m.phi_deg, m.cohesion * 1e-3);
  else
    std::snprintf(buf, sizeof buf,
                  "phi = %.2f +- %.2f deg, c = %.2f +- %.2f kPa (%d points, R^2 = %.4f)",
                  m.phi_deg, m.phi_se_deg, m.cohesion * 1e-3, m.cohesion_se * 1e-3, m.points,
                  m.r2);
  return buf;
}

void write_campaign_report(const std::string& out_dir, const std::string& base_name,
                           const std::vector<double>& sizes_mm,
                           const std::vector<CampaignEntry>& entries, double wall_seconds) {
  const fs::path out = out_dir;
  std::string csv = csv_header();
  std::string md = "# Direct shear campaign\n\nBase scene: `" + base_name + "`; " +
                   std::to_string(entries.size()) + " tests; wall time of the tests run now: " +
                   fmt("%.0f", wall_seconds) + " s.\n\n## Tests\n\n" + kTestsIntro;
  std::string ens_csv =
      "diameter_mm,normal_stress_kPa,specimens,peak_friction_angle_deg,peak_ci95,"
      "residual_friction_angle_deg,residual_ci95,peak_tau_kPa,peak_tau_ci95,residual_tau_kPa,"
      "residual_tau_ci95,max_dilatancy_angle_deg,max_dilatancy_ci95,"
      "residual_friction_angle_plane_deg,residual_plane_ci95,wall_load_percent,wall_load_ci95,"
      "critical_state_reached,tests_with_dynamic_events\n";
  std::string ens_md =
      "\n## Over the specimens (the valid tests: mean ± 95 % Student interval)\n\n"
      "| d (mm) | σ (kPa) | specimens | φ peak (°) | φ residual (°) | ψ max (°) | critical "
      "state reached | with dynamic events |\n|---|---|---|---|---|---|---|---|\n";
  std::string env_csv = "diameter_mm,strength,specimens,phi_deg,phi_spread_deg,c_kPa,c_spread_kPa,spread\n";
  std::string fits = "\n## Mohr-Coulomb envelopes, τ = c + σ tan φ\n\n"
                     "| d (mm) | strength | φ (°) | c (kPa) | specimens | fit |\n"
                     "|---|---|---|---|---|---|\n";
  std::vector<EnvelopeSeries> peaks, residuals;
  for (double d : sizes_mm) {
    std::vector<ShearCurve> curves;
    std::vector<const CampaignEntry*> tests;
    std::map<double, std::vector<const CampaignEntry*>> by_stress;
    std::int64_t first_seed = -1;
    for (const CampaignEntry& e : entries) {
      if (e.d_mm != d) continue;
      if (first_seed < 0) first_seed = e.seed;
      csv += csv_row(e);
      md += md_row(e);
      if (e.seed == first_seed) curves.push_back({fmt("%g kPa", e.s_kpa), e.rows, e.summary});
      if (!e.summary.valid) continue;  // listed above, left out of what follows
      by_stress[e.s_kpa].push_back(&e);
      tests.push_back(&e);
    }
    for (const auto& [s_kpa, at] : by_stress) ens_csv += ensemble_row(d, s_kpa, at, ens_md);
    const std::string stem = fmt("d%gmm", d);
    write_size_plots((out / (stem + "_stress.png")).string(),
                     (out / (stem + "_dilation.png")).string(), fmt("Glass beads d = %g mm", d),
                     curves);
    for (bool residual : {false, true}) {
      Envelope env = fit_envelope(d, tests, residual);
      fits += env.table_row;
      env_csv += env.csv_row;
      if (env.fitted) (residual ? residuals : peaks).push_back(env.series);
    }
  }
  write_envelope_plot((out / "mohr_coulomb.png").string(), "peak", peaks);
  write_envelope_plot((out / "mohr_coulomb_residual.png").string(), "residual", residuals);
  write_file_atomic((out / "summary.csv").string(), csv);
  write_file_atomic((out / "ensemble.csv").string(), ens_csv);
  write_file_atomic((out / "envelopes.csv").string(), env_csv);
  write_file_atomic((out / "summary.md").string(), md + ens_md + fits);
}

}  // namespace simsols
