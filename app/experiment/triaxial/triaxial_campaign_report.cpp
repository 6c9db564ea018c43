#include "app/experiment/triaxial/triaxial_campaign_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "app/experiment/shear_box/campaign_report.h"
#include "app/experiment/shear_box/study_stats.h"
#include "render/plot/chart.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

namespace fs = std::filesystem;
constexpr auto fmt = format_number;  // printf conversion of one number (output.h)
constexpr double kPi = 3.14159265358979323846;

std::string csv_row(const TriaxialCampaignEntry& e) {
  const TriaxialSummary& s = e.summary;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%g,%lld,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                e.s_kpa, static_cast<long long>(e.seed), e.beads, s.initial_void_ratio, s.peak_angle, s.max_angle, s.peak_q_over_p,
                100 * s.peak_axial_strain, s.peak_sigma1 * 1e-3, s.peak_sigma3 * 1e-3,
                s.critical_angle, s.critical_void_ratio, s.critical_p * 1e-3,
                s.critical_sigma1 * 1e-3, s.critical_sigma3 * 1e-3, s.max_dilatancy_angle,
                100 * s.wall_internal_gap, s.wall_seconds);
  return buf;
}

std::string md_row(const TriaxialCampaignEntry& e) {
  const TriaxialSummary& s = e.summary;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "| %g | %lld | %d | %.3f | %.2f | %.2f | %.3f | %.1f | %.2f | %.3f | %.1f | %.2f | %.1f / "
                "%.1f | %.0f |\n",
                e.s_kpa, static_cast<long long>(e.seed), e.beads, s.initial_void_ratio, s.peak_angle, s.max_angle, s.peak_q_over_p,
                100 * s.peak_axial_strain, s.critical_angle, s.critical_void_ratio,
                s.critical_p * 1e-3, s.max_dilatancy_angle, 100 * s.median_wall_internal_gap,
                100 * s.wall_internal_gap, s.wall_seconds);
  return buf;
}

// A test's label in the plots: its stress, and its seed when there are several.
std::string test_label(const TriaxialCampaignEntry& e, bool seeds) {
  return "σ3 = " + fmt("%g", e.s_kpa) + " kPa" + (seeds ? ", seed " + std::to_string(e.seed) : "");
}

bool several_seeds(const std::vector<TriaxialCampaignEntry>& entries) {
  for (const TriaxialCampaignEntry& e : entries)
    if (e.seed != entries.front().seed) return true;
  return false;
}

plot::Series curve(const TriaxialCampaignEntry& e, bool seeds, double (*y)(const TriaxialRow&)) {
  plot::Series s;
  s.label = test_label(e, seeds);
  for (const TriaxialRow& r : e.rows) {
    s.x.push_back(100 * r.axial_strain);
    s.y.push_back(y(r));
  }
  return s;
}

void write_curves(const fs::path& out, const std::string& title,
                  const std::vector<TriaxialCampaignEntry>& entries) {
  plot::Chart eta, vol;
  eta.title = title + ": stress ratio";
  vol.title = title + ": volume change (compression up)";
  eta.x_label = vol.x_label = "Axial strain εa (%)";
  eta.y_label = "q/p′";
  vol.y_label = "Volumetric strain εv (%)";
  const bool seeds = several_seeds(entries);
  for (const TriaxialCampaignEntry& e : entries) {
    eta.series.push_back(
        curve(e, seeds, [](const TriaxialRow& r) { return r.p > 0 ? r.q / r.p : NAN; }));
    vol.series.push_back(
        curve(e, seeds, [](const TriaxialRow& r) { return 100 * r.volumetric_strain; }));
  }
  plot::write_chart_png(eta, (out / "stress_ratio.png").string());
  plot::write_chart_png(vol, (out / "volumetric.png").string());
}

// The upper half of the circle through s3 and s1 (kPa).
plot::Series half_circle(const std::string& label, double s1, double s3) {
  plot::Series c;
  c.label = label;
  const double centre = 0.5 * (s1 + s3), radius = 0.5 * (s1 - s3);
  for (int i = 0; i <= 90; ++i) {
    const double a = kPi * i / 90;
    c.x.push_back(centre - radius * std::cos(a));
    c.y.push_back(radius * std::sin(a));
  }
  return c;
}

// Mohr circles (kPa) and the envelope tangent to them, on equal scales.
void write_mohr_plot(const fs::path& png, const std::string& which,
                     const std::vector<TriaxialCampaignEntry>& entries, const MohrCoulomb& fit) {
  plot::Chart c;
  c.title = "Mohr circles at the " + which + " and the envelope";
  c.x_label = "Normal stress σ′ (kPa)";
  c.y_label = "Shear stress τ (kPa)";
  const bool peak = which == "peak", seeds = several_seeds(entries);
  double s_max = 0;
  for (const TriaxialCampaignEntry& e : entries) {
    const double s1 = 1e-3 * (peak ? e.summary.peak_sigma1 : e.summary.critical_sigma1);
    const double s3 = 1e-3 * (peak ? e.summary.peak_sigma3 : e.summary.critical_sigma3);
    c.series.push_back(half_circle(test_label(e, seeds), s1, s3));
    s_max = std::max(s_max, s1);
  }
  const double x_hi = 1.05 * s_max;
  if (fit.points >= 2) {
    plot::Series env;
    env.label = "φ = " + fmt("%.1f", fit.phi_deg) + "°, c = " + fmt("%.1f", fit.cohesion * 1e-3) +
                " kPa";
    env.dashed = true;
    env.color = plot::Color{0, 0, 0, 255};
    for (double x : {0.0, x_hi}) {
      env.x.push_back(x);
      env.y.push_back(fit.cohesion * 1e-3 + x * fit.tan_phi);
    }
    c.series.push_back(env);
  }
  c.x_min = 0;
  c.x_max = x_hi;
  c.y_min = 0;
  // Equal scales: the y range that makes a kPa as tall as it is wide.
  const plot::ChartLayout l = plot::chart_layout(c);
  c.y_max = x_hi * double(l.bottom - l.top) / double(l.right - l.left);
  plot::write_chart_png(c, png.string());
}

void write_csl_plot(const fs::path& png, const std::vector<TriaxialCampaignEntry>& entries,
                    const CriticalStateLine& csl) {
  plot::Chart c;
  c.title = "Void ratio and mean stress: paths, critical states and the critical state line";
  c.x_label = "Mean stress p′ (kPa)";
  c.y_label = "Void ratio e";
  c.x_log = true;
  double p_lo = 1e300, p_hi = 0;
  const bool seeds = several_seeds(entries);
  for (const TriaxialCampaignEntry& e : entries) {
    plot::Series path;
    path.label = test_label(e, seeds);
    for (const TriaxialRow& r : e.rows) {
      path.x.push_back(r.p * 1e-3);
      path.y.push_back(r.void_ratio);
      p_lo = std::min(p_lo, r.p * 1e-3);
      p_hi = std::max(p_hi, r.p * 1e-3);
    }
    c.series.push_back(path);
    c.markers.push_back({e.summary.critical_p * 1e-3, e.summary.critical_void_ratio, ""});
  }
  if (csl.points >= 2 && p_hi > 0) {
    plot::Series line;
    line.label = "CSL e = " + fmt("%.3f", csl.gamma) + " − " + fmt("%.4f", csl.lambda) + " ln p′";
    line.dashed = true;
    line.color = plot::Color{0, 0, 0, 255};
    for (double p : {p_lo, p_hi}) {
      line.x.push_back(p);
      line.y.push_back(csl.gamma - csl.lambda * std::log(p));
    }
    c.series.push_back(line);
  }
  plot::write_chart_png(c, png.string());
}

std::string describe_csl(const CriticalStateLine& c) {
  if (c.points < 2) return "needs two or more tests";
  char buf[200];
  if (c.points == 2)
    std::snprintf(buf, sizeof buf, "Γ = %.4f, λ = %.5f (2 points: the line through them)", c.gamma,
                  c.lambda);
  else
    std::snprintf(buf, sizeof buf, "Γ = %.4f, λ = %.5f ± %.5f (%d points, R² = %.4f)", c.gamma,
                  c.lambda, c.lambda_se, c.points, c.r2);
  return buf;
}

// One specimen's fits over its tests: the envelopes at the peak and at the
// critical state, and its critical state line.
struct SpecimenFits {
  std::int64_t seed = 0;
  MohrCoulomb peak, critical;
  CriticalStateLine csl;
};

std::vector<SpecimenFits> specimen_fits(const std::vector<TriaxialCampaignEntry>& entries) {
  std::map<std::int64_t, std::vector<const TriaxialCampaignEntry*>> by_seed;
  for (const TriaxialCampaignEntry& e : entries) by_seed[e.seed].push_back(&e);
  std::vector<SpecimenFits> fits;
  for (const auto& [seed, tests] : by_seed) {
    std::vector<double> p1, p3, c1, c3, cp, ce;
    for (const TriaxialCampaignEntry* e : tests) {
      p1.push_back(e->summary.peak_sigma1);
      p3.push_back(e->summary.peak_sigma3);
      c1.push_back(e->summary.critical_sigma1);
      c3.push_back(e->summary.critical_sigma3);
      cp.push_back(e->summary.critical_p);
      ce.push_back(e->summary.critical_void_ratio);
    }
    fits.push_back({seed, fit_mohr_circles(p1, p3), fit_mohr_circles(c1, c3),
                    fit_critical_state_line(cp, ce)});
  }
  return fits;
}

// What the campaign reports of one strength: one specimen's fit with its
// standard errors, or, over several, the mean of the specimens' fits with
// its 95 % Student interval (the specimens are the replicates; the tests of
// one specimen share its packing and are not independent).
struct Strength {
  SpecimensEnvelope env;  // shear_box/campaign_report.h
  MohrCoulomb line;       // drawn: one specimen's fit, or the mean's phi and c
  std::string text;
};

Strength strength(const std::vector<SpecimenFits>& fits, MohrCoulomb SpecimenFits::*which) {
  Strength st;
  std::vector<MohrCoulomb> fitted;
  for (const SpecimenFits& f : fits)
    if ((f.*which).points >= 2) fitted.push_back(f.*which);
  st.env = specimens_envelope(fitted);
  if (fitted.empty()) {
    st.text = "needs two or more tests";
  } else if (!st.env.ci95()) {
    st.line = fitted[0];
    st.text = describe_fit(st.line) + "; one specimen: its fit's standard errors, not an interval "
              "on the material (--seeds)";
  } else {
    const SpecimensEnvelope& e = st.env;
    st.line = fitted.back();  // its point count: drawn
    st.line.phi_deg = e.phi_deg;
    st.line.tan_phi = std::tan(e.phi_deg * kPi / 180);
    st.line.cohesion = e.c_kpa * 1e3;
    st.text = "phi = " + fmt("%.2f", e.phi_deg) + " +- " + fmt("%.2f", e.phi_spread_deg) +
              " deg, c = " + fmt("%.2f", e.c_kpa) + " +- " + fmt("%.2f", e.c_spread_kpa) +
              " kPa (mean of " + std::to_string(e.specimens) + " specimens' fits +- 95 % interval)";
  }
  return st;
}

// The critical state line: one specimen's, or the mean of the specimens'
// Gamma and lambda with their 95 % intervals.
CriticalStateLine mean_line(const std::vector<SpecimenFits>& fits, std::string& text) {
  std::vector<double> g, l;
  CriticalStateLine one;
  for (const SpecimenFits& f : fits)
    if (f.csl.points >= 2) {
      one = f.csl;
      g.push_back(f.csl.gamma);
      l.push_back(f.csl.lambda);
    }
  if (g.size() < 2) {
    text = describe_csl(one);
    return one;
  }
  const Interval ig = mean_ci95(g), il = mean_ci95(l);
  text = "Γ = " + fmt("%.4f", ig.mean) + " ± " + fmt("%.4f", ig.half_width) + ", λ = " +
         fmt("%.5f", il.mean) + " ± " + fmt("%.5f", il.half_width) + " (mean of " +
         std::to_string(g.size()) + " specimens' lines ± 95 % interval)";
  one.gamma = ig.mean;
  one.lambda = il.mean;
  one.points = 2;
  return one;
}

// envelopes.csv: each strength's phi and c with their spread (ci95 over
// specimens, or se for one specimen's fit), as the shear campaign writes it.
std::string envelopes_csv(const Strength& peak, const Strength& critical) {
  std::string csv = "strength,specimens,phi_deg,phi_spread_deg,c_kPa,c_spread_kPa,spread\n";
  for (const auto& [name, st] : {std::pair<const char*, const Strength*>{"peak", &peak},
                                 {"critical", &critical}}) {
    const SpecimensEnvelope& e = st->env;
    csv += std::string(name) + "," + std::to_string(e.specimens);
    if (e.specimens == 0) {
      csv += ",,,,,\n";
      continue;
    }
    csv += "," + fmt("%.6f", e.phi_deg) + "," + fmt("%.6f", e.phi_spread_deg) + "," +
           fmt("%.6f", e.c_kpa) + "," + fmt("%.6f", e.c_spread_kpa) + "," +
           (e.ci95() ? "ci95" : "se") + "\n";
  }
  return csv;
}

}  // namespace

void write_triaxial_campaign_report(const std::string& out_dir, const std::string& base_name,
                                    const std::vector<TriaxialCampaignEntry>& entries,
                                    double wall_seconds) {
  const fs::path out = out_dir;
  std::string csv =
      "sigma3_kPa,seed,beads,e0,peak_phi_deg,max_phi_deg,peak_q_over_p,peak_axial_strain_percent,"
      "peak_sigma1_kPa,peak_sigma3_kPa,critical_phi_deg,critical_void_ratio,critical_p_kPa,"
      "critical_sigma1_kPa,critical_sigma3_kPa,max_dilatancy_deg,wall_internal_gap_percent,"
      "wall_seconds\n";
  std::string md = "# Triaxial campaign\n\nBase scene: `" + base_name + "`; " +
                   std::to_string(entries.size()) + " tests; wall time of the tests run now: " +
                   fmt("%.0f", wall_seconds) +
                   " s. Peak: the largest running median of the mobilised angle over 1 % of "
                   "axial strain; largest: the largest angle of any row (a jamming event can "
                   "make it); critical state: the mean over the last 20 % of the axial strain; "
                   "plates vs Love-Weber stress: the median and the largest gap over the rows, "
                   "as % of p′ (docs/triaxial.md).\n\n"
                   "| σ3 (kPa) | seed | beads | e0 | φ peak (°) | φ largest (°) | q/p′ peak | εa peak (%) "
                   "| φ cs (°) | e cs | p′ cs (kPa) | ψ max (°) | plates vs LW, median / largest "
                   "(%) | wall (s) |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const TriaxialCampaignEntry& e : entries) {
    csv += csv_row(e);
    md += md_row(e);
  }
  const std::vector<SpecimenFits> fits = specimen_fits(entries);
  const Strength peak = strength(fits, &SpecimenFits::peak);
  const Strength critical = strength(fits, &SpecimenFits::critical);
  std::string csl_text;
  const CriticalStateLine csl = mean_line(fits, csl_text);
  md += "\n## Envelopes tangent to the Mohr circles, τ = c + σ′ tan φ\n\n"
        "Each specimen's envelope is fitted to its own tests; over several specimens the "
        "strength is the mean of their fits with its 95 % interval.\n\n"
        "- peak: " + peak.text + "\n- critical state: " + critical.text +
        "\n\n## Critical state line, e = Γ − λ ln(p′ / 1 kPa)\n\n- " + csl_text + "\n";
  std::printf("Mohr-Coulomb envelope (peak): %s\n", peak.text.c_str());
  std::printf("Mohr-Coulomb envelope (critical state): %s\n", critical.text.c_str());
  std::printf("critical state line: %s\n", csl_text.c_str());
  write_curves(out, "Triaxial campaign", entries);
  write_mohr_plot(out / "mohr_peak.png", "peak", entries, peak.line);
  write_mohr_plot(out / "mohr_critical.png", "critical state", entries, critical.line);
  write_csl_plot(out / "csl.png", entries, csl);
  write_file_atomic((out / "envelopes.csv").string(), envelopes_csv(peak, critical));
  write_file_atomic((out / "summary.csv").string(), csv);
  write_file_atomic((out / "summary.md").string(), md);
}

}  // namespace simsols
