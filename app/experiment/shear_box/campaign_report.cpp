#include "app/experiment/shear_box/campaign_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "solver/io/output.h"
#include "app/experiment/shear_box/shear_plots.h"

namespace simsols {
namespace {

constexpr auto fmt = format_number;  // printf conversion of one number (output.h)

namespace fs = std::filesystem;

std::string csv_header() {
  return "diameter_mm,layers,normal_stress_kPa,peak_tau_kPa,peak_tau_over_sigma,"
         "peak_friction_angle_deg,peak_displacement_mm,max_tau_over_sigma,"
         "max_friction_angle_deg,max_displacement_mm,residual_tau_kPa,"
         "residual_friction_angle_deg,max_dilatancy_angle_deg,max_inertial_number,"
         "sigma_band_min_percent,sigma_band_max_percent,sigma_rms_percent,valid,"
         "start_tau_over_sigma,beads,wall_seconds\n";
}

std::string csv_row(const CampaignEntry& e) {
  const ShearSummary& s = e.summary;
  std::ostringstream o;
  o << fmt("%g", e.d_mm) << ',' << e.layers << ',' << fmt("%g", e.s_kpa) << ','
    << fmt("%.6g", s.peak_tau * 1e-3) << ',' << fmt("%.6g", s.peak_ratio) << ','
    << fmt("%.4f", s.peak_angle) << ',' << fmt("%.6g", s.peak_displacement * 1e3) << ','
    << fmt("%.6g", s.max_ratio) << ',' << fmt("%.4f", s.max_angle) << ','
    << fmt("%.6g", s.max_displacement * 1e3) << ',' << fmt("%.6g", s.residual_tau * 1e-3) << ','
    << fmt("%.4f", s.residual_angle) << ',' << fmt("%.4f", s.max_dilatancy_angle) << ','
    << fmt("%.4g", s.max_inertial_number) << ',' << fmt("%.3f", 100 * s.sigma_band_lo) << ','
    << fmt("%.3f", 100 * s.sigma_band_hi) << ',' << fmt("%.3f", 100 * s.sigma_rms) << ','
    << (s.valid ? "yes" : "no") << ',' << fmt("%.4f", s.start_ratio) << ',' << e.beads << ','
    << fmt("%.1f", s.wall_seconds) << '\n';
  return o.str();
}

std::string md_row(const CampaignEntry& e) {
  const ShearSummary& s = e.summary;
  std::ostringstream o;
  o << "| " << fmt("%g", e.d_mm) << " | " << fmt("%g", e.s_kpa) << " | "
    << fmt("%.1f", s.peak_tau * 1e-3) << " | " << fmt("%.2f", s.peak_angle) << " at "
    << fmt("%.2f", s.peak_displacement * 1e3) << " mm | " << fmt("%.2f", s.max_angle) << " | "
    << fmt("%.2f", s.residual_angle) << " | " << fmt("%.2f", s.max_dilatancy_angle) << " | "
    << fmt("%+.2f", 100 * s.sigma_band_lo) << " / " << fmt("%+.2f", 100 * s.sigma_band_hi)
    << " (" << fmt("%.2f", 100 * s.sigma_rms) << ")" << (s.valid ? "" : " **invalid**") << " | "
    << fmt("%.3f", s.start_ratio) << " | " << fmt("%.2g", s.max_inertial_number) << " | "
    << fmt("%.0f", s.wall_seconds) << " |\n";
  return o.str();
}

std::string se_text(double value, double se, const char* f) {
  return fmt(f, value) + (std::isfinite(se) ? " ± " + fmt(f, se) : "");
}

// One size's envelope of one strength: the table row, the plot series.
struct Envelope {
  std::string table_row;
  EnvelopeSeries series;
  bool fitted = false;
};

Envelope fit_envelope(double d_mm, const std::vector<const CampaignEntry*>& tests, bool residual) {
  Envelope e;
  e.series.label = fmt("%g mm", d_mm);
  for (const CampaignEntry* t : tests) {
    e.series.sigma.push_back(t->summary.normal_stress_target);
    e.series.tau.push_back(residual ? t->summary.residual_tau : t->summary.peak_tau);
  }
  const std::string which = residual ? "residual" : "peak";
  if (e.series.sigma.size() < 2) {
    e.table_row = "| " + fmt("%g", d_mm) + " | " + which + " | – | – | " +
                  std::to_string(e.series.sigma.size()) + " | needs two or more stresses |\n";
    std::printf("Mohr-Coulomb d = %g mm (%s): needs two or more normal stresses\n", d_mm,
                which.c_str());
    return e;
  }
  const MohrCoulomb mc = fit_mohr_coulomb(e.series.sigma, e.series.tau);
  e.series.cohesion = mc.cohesion;
  e.series.tan_phi = mc.tan_phi;
  e.fitted = true;
  e.table_row = "| " + fmt("%g", d_mm) + " | " + which + " | " +
                se_text(mc.phi_deg, mc.phi_se_deg, "%.2f") + " | " +
                se_text(mc.cohesion * 1e-3, mc.cohesion_se * 1e-3, "%.2f") + " | " +
                std::to_string(mc.points) + " | " +
                (mc.exact ? std::string("two points: the line through them, no error estimate")
                          : "R² = " + fmt("%.4f", mc.r2)) +
                " |\n";
  std::printf("Mohr-Coulomb d = %g mm (%s): %s\n", d_mm, which.c_str(), describe_fit(mc).c_str());
  return e;
}

}  // namespace

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
                   fmt("%.0f", wall_seconds) +
                   " s. Peak: the first peak of τ/σ; largest: the largest τ/σ of the test; "
                   "residual: the mean over the last 20 % of the shear; σ band: the row means' "
                   "deviation from the target, with its RMS; a test beyond ±" +
                   fmt("%.0f", 100 * kValidSigmaBand) +
                   " % is invalid and left out of the envelopes.\n\n"
                   "| d (mm) | σ (kPa) | τ peak (kPa) | φ peak (°) | φ largest (°) | "
                   "φ residual (°) | ψ max (°) | σ band (RMS) (%) | τ/σ at rest | I max | "
                   "wall (s) |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::string fits = "\n## Mohr-Coulomb envelopes, τ = c + σ tan φ (± one standard error)\n\n"
                     "| d (mm) | strength | φ (°) | c (kPa) | points | fit |\n"
                     "|---|---|---|---|---|---|\n";
  std::vector<EnvelopeSeries> peaks, residuals;
  for (double d : sizes_mm) {
    std::vector<ShearCurve> curves;
    std::vector<const CampaignEntry*> tests;
    for (const CampaignEntry& e : entries) {
      if (e.d_mm != d) continue;
      csv += csv_row(e);
      md += md_row(e);
      curves.push_back({fmt("%g kPa", e.s_kpa), e.rows, e.summary});
      if (e.summary.valid) tests.push_back(&e);
    }
    const std::string stem = fmt("d%gmm", d);
    write_size_plots((out / (stem + "_stress.png")).string(),
                     (out / (stem + "_dilation.png")).string(), fmt("Glass beads d = %g mm", d),
                     curves);
    for (bool residual : {false, true}) {
      Envelope env = fit_envelope(d, tests, residual);
      fits += env.table_row;
      if (env.fitted) (residual ? residuals : peaks).push_back(env.series);
    }
  }
  write_envelope_plot((out / "mohr_coulomb.png").string(), "peak", peaks);
  write_envelope_plot((out / "mohr_coulomb_residual.png").string(), "residual", residuals);
  write_file_atomic((out / "summary.csv").string(), csv);
  write_file_atomic((out / "summary.md").string(), md + fits);
}

}  // namespace simsols
