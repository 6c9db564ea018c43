#include "app/experiment/triaxial/triaxial_plots.h"

#include <filesystem>

#include "render/plot/chart.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

constexpr auto fmt = format_number;  // printf conversion of one number (output.h)

plot::Series column(const std::string& label, const std::vector<TriaxialRow>& rows,
                    double (*x)(const TriaxialRow&), double (*y)(const TriaxialRow&)) {
  plot::Series s;
  s.label = label;
  for (const TriaxialRow& r : rows) {
    s.x.push_back(x(r));
    s.y.push_back(y(r));
  }
  return s;
}

double strain_pct(const TriaxialRow& r) { return 100 * r.axial_strain; }
double volumetric_pct(const TriaxialRow& r) { return 100 * r.volumetric_strain; }
double ratio(const TriaxialRow& r) { return r.p > 0 ? r.q / r.p : NAN; }
double q_kpa(const TriaxialRow& r) { return r.q * 1e-3; }
double p_kpa(const TriaxialRow& r) { return r.p * 1e-3; }
double void_ratio(const TriaxialRow& r) { return r.void_ratio; }

void write(plot::Chart c, const std::filesystem::path& png) { plot::write_chart_png(c, png.string()); }

}  // namespace

void write_triaxial_plots(const std::string& dir, const std::string& title,
                          const std::vector<TriaxialRow>& rows, const TriaxialSummary& s) {
  const std::filesystem::path d = dir;
  const std::string x_label = "Axial strain εa (%)";
  plot::Chart eta;
  eta.title = title + ": stress ratio";
  eta.x_label = x_label;
  eta.y_label = "q/p′";
  eta.series.push_back(column("q/p′", rows, strain_pct, ratio));
  eta.markers.push_back({100 * s.peak_axial_strain, s.peak_q_over_p,
                         "peak φ = " + fmt("%.1f", s.peak_angle) + "°"});
  eta.legend = false;
  write(eta, d / "stress_ratio.png");

  plot::Chart dev;
  dev.title = title + ": deviator and mean stress";
  dev.x_label = x_label;
  dev.y_label = "Stress (kPa)";
  dev.series.push_back(column("q", rows, strain_pct, q_kpa));
  dev.series.push_back(column("p′", rows, strain_pct, p_kpa));
  write(dev, d / "deviator.png");

  plot::Chart vol;
  vol.title = title + ": volume change (compression up)";
  vol.x_label = x_label;
  vol.y_label = "Volumetric strain εv (%)";
  vol.series.push_back(column("εv", rows, strain_pct, volumetric_pct));
  vol.legend = false;
  write(vol, d / "volumetric.png");

  plot::Chart csl;
  csl.title = title + ": void ratio and mean stress";
  csl.x_label = "Mean stress p′ (kPa)";
  csl.y_label = "Void ratio e";
  csl.x_log = true;
  csl.series.push_back(column("path", rows, p_kpa, void_ratio));
  csl.markers.push_back({s.critical_p * 1e-3, s.critical_void_ratio,
                         "critical state e = " + fmt("%.3f", s.critical_void_ratio)});
  csl.legend = false;
  write(csl, d / "e_log_p.png");
}

}  // namespace simsols
