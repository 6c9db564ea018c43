#include "app/experiment/shear_box/shear_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "render/plot/chart.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

constexpr auto fmt = format_number;  // printf conversion of one number (output.h)

// "peak 0.704 (φ = 35.2°)"
std::string ratio_label(const std::string& what, double ratio, double degrees) {
  return what + " " + fmt("%.3f", ratio) + " (φ = " + fmt("%.1f", degrees) + "°)";
}

plot::Series column(const std::string& label, const std::vector<ShearRow>& rows,
                    double (*y)(const ShearRow&)) {
  plot::Series s;
  s.label = label;
  for (const ShearRow& r : rows) {
    s.x.push_back(r.displacement * 1e3);
    s.y.push_back(y(r));
  }
  return s;
}

// The row at displacement `x` (displacements increase, so at most one
// matches); null when there is none.
const ShearRow* row_at(const std::vector<ShearRow>& rows, double x) {
  for (const ShearRow& r : rows)
    if (std::fabs(r.displacement - x) < 1e-12) return &r;
  return nullptr;
}
const ShearRow* peak_row(const std::vector<ShearRow>& rows, const ShearSummary& s) {
  return s.peak_ratio > 0 ? row_at(rows, s.peak_displacement) : nullptr;
}
// The largest tau/sigma when it comes after the peak and exceeds it.
const ShearRow* later_max_row(const std::vector<ShearRow>& rows, const ShearSummary& s) {
  return s.max_ratio > s.peak_ratio && s.max_displacement > s.peak_displacement
             ? row_at(rows, s.max_displacement)
             : nullptr;
}

double tau_kpa(const ShearRow& r) { return r.tau * 1e-3; }
double ratio(const ShearRow& r) { return r.sigma > 0 ? r.tau / r.sigma : NAN; }
double dilation_mm(const ShearRow& r) { return r.dilation * 1e3; }

}  // namespace

void write_shear_plots(const std::string& dir, const std::string& title,
                       const std::vector<ShearRow>& rows, const ShearSummary& s) {
  const std::filesystem::path d = dir;
  const std::string x_label = "Horizontal displacement (mm)";
  plot::Chart tau;
  tau.title = title + ": shear stress";
  tau.x_label = x_label;
  tau.y_label = "Shear stress τ (kPa)";
  tau.series.push_back(column("τ on the nominal area", rows, tau_kpa));
  // the peak (the first peak of tau/sigma) and a later, larger maximum, on
  // both curves
  const ShearRow* peak = peak_row(rows, s);
  const ShearRow* later = later_max_row(rows, s);
  if (peak)
    tau.markers.push_back({peak->displacement * 1e3, s.peak_tau * 1e-3,
                           "peak φ = " + fmt("%.1f", s.peak_angle) + "°"});
  if (later)
    tau.markers.push_back({later->displacement * 1e3, later->tau * 1e-3,
                           "later maximum φ = " + fmt("%.1f", s.max_angle) + "°"});
  tau.legend = false;
  plot::write_chart_png(tau, (d / "shear_stress.png").string());

  plot::Chart rat;
  rat.title = title + ": stress ratio";
  rat.x_label = x_label;
  rat.y_label = "τ/σ";
  rat.series.push_back(column("τ/σ", rows, ratio));
  if (peak)
    rat.markers.push_back({peak->displacement * 1e3, s.peak_ratio,
                           ratio_label("peak", s.peak_ratio, s.peak_angle)});
  if (later)
    rat.markers.push_back({later->displacement * 1e3, s.max_ratio,
                           ratio_label("later maximum", s.max_ratio, s.max_angle)});
  plot::Series residual;
  residual.label = ratio_label(s.critical_state ? "critical state" : "residual (volume still changing)",
                               s.residual_ratio, s.residual_angle);
  if (!rows.empty()) {
    const double end = rows.back().displacement * 1e3;
    residual.x = {s.residual_from * 1e3, end};
    residual.y = {s.residual_ratio, s.residual_ratio};
    residual.dashed = true;
    rat.series.push_back(residual);
  }
  plot::write_chart_png(rat, (d / "shear_ratio.png").string());

  plot::Chart dil;
  dil.title = title + ": dilation";
  dil.x_label = x_label;
  dil.y_label = "Vertical displacement (mm), dilation +";
  dil.series.push_back(column("platen", rows, dilation_mm));
  dil.legend = false;
  plot::write_chart_png(dil, (d / "dilation.png").string());
}

void write_size_plots(const std::string& stress_png, const std::string& dilation_png,
                      const std::string& title, const std::vector<ShearCurve>& curves) {
  plot::Chart tau, dil;
  tau.title = title;
  tau.x_label = dil.x_label = "Horizontal displacement (mm)";
  tau.y_label = "Shear stress τ (kPa)";
  dil.title = title;
  dil.y_label = "Vertical displacement (mm), dilation +";
  for (const ShearCurve& c : curves) {
    tau.series.push_back(column(c.label, c.rows, tau_kpa));
    dil.series.push_back(column(c.label, c.rows, dilation_mm));
    if (const ShearRow* peak = peak_row(c.rows, c.summary))
      tau.markers.push_back({peak->displacement * 1e3, c.summary.peak_tau * 1e-3, ""});
  }
  plot::write_chart_png(tau, stress_png);
  plot::write_chart_png(dil, dilation_png);
}

void write_envelope_plot(const std::string& png, const std::string& which,
                         const std::vector<EnvelopeSeries>& sizes) {
  plot::Chart c;
  c.title = "Mohr-Coulomb envelopes (" + which + ")";
  c.x_label = "Normal stress σ (kPa)";
  c.y_label = "Shear stress τ (kPa), " + which;
  double s_max = 0;
  for (const EnvelopeSeries& e : sizes)
    for (double v : e.sigma) s_max = std::max(s_max, v);
  for (size_t k = 0; k < sizes.size(); ++k) {
    const EnvelopeSeries& e = sizes[k];
    plot::Series pts;
    pts.label = e.label + ": φ = " + fmt("%.1f", std::atan(e.tan_phi) * 180 / M_PI) + "°, c = " +
                fmt("%.1f", e.cohesion * 1e-3) + " kPa";
    pts.color = plot::palette_color(k);
    pts.line = false;
    pts.markers = true;
    for (size_t i = 0; i < e.sigma.size(); ++i) {
      pts.x.push_back(e.sigma[i] * 1e-3);
      pts.y.push_back(e.tau[i] * 1e-3);
    }
    plot::Series fit;
    fit.color = plot::palette_color(k);
    fit.dashed = true;
    fit.x = {0, s_max * 1e-3 * 1.05};
    fit.y = {e.cohesion * 1e-3, (e.cohesion + s_max * 1.05 * e.tan_phi) * 1e-3};
    c.series.push_back(pts);
    c.series.push_back(fit);
  }
  c.x_min = 0;
  c.y_min = 0;
  plot::write_chart_png(c, png);
}

}  // namespace simsols
