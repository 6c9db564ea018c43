#include "app/experiment/oedometer/oedometer_plots.h"

#include <algorithm>
#include <filesystem>

#include "render/plot/chart.h"
#include "solver/io/output.h"

namespace simsols {
namespace {

constexpr auto fmt = format_number;  // printf conversion of one number (output.h)

// The ends of the steps on one branch, as a line with markers.
plot::Series branch(const std::string& label, const OedometerSummary& s, bool loading,
                    double (*y)(const OedometerStep&)) {
  plot::Series out;
  out.label = label;
  out.markers = true;
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const OedometerStep& st = s.steps[i];
    // the unloading branch starts at the largest step, the last loading one
    const bool last_loading = st.loading && i + 1 < s.steps.size() && !s.steps[i + 1].loading;
    if (loading ? !st.loading : !(last_loading || !st.loading)) continue;
    out.x.push_back(st.sigma_top * 1e-3);
    out.y.push_back(y(st));
  }
  return out;
}

double void_ratio(const OedometerStep& s) { return s.void_ratio; }
double k0(const OedometerStep& s) { return s.k0; }

void e_log_sigma(const std::filesystem::path& d, const std::string& title,
                 const std::vector<OedometerRow>& rows, const OedometerSummary& s) {
  plot::Chart c;
  c.title = title + ": compression curve";
  c.x_label = "Vertical stress σ′v (kPa)";
  c.y_label = "Void ratio e";
  c.x_log = true;
  plot::Series path;
  path.label = "every row";
  path.color = plot::Color{190, 190, 190, 255};
  // from the end of the first step (the seating before it would set the scale)
  bool seated = false;
  for (const OedometerRow& r : rows) {
    if (seated && r.sigma_top > 0) {
      path.x.push_back(r.sigma_top * 1e-3);
      path.y.push_back(r.void_ratio);
    }
    seated = seated || r.end_of_step != 0;
  }
  c.series.push_back(path);
  c.series.push_back(branch("loading, Cc = " + fmt("%.4f", s.cc), s, true, void_ratio));
  if (s.cs_points > 0)
    c.series.push_back(branch("unloading, Cs = " + fmt("%.4f", s.cs), s, false, void_ratio));
  plot::write_chart_png(c, (d / "e_log_sigma.png").string());
}

void k0_plot(const std::filesystem::path& d, const std::string& title,
             const OedometerSummary& s) {
  plot::Chart c;
  c.title = title + ": lateral stress ratio";
  c.x_label = "Vertical stress σ′v (kPa)";
  c.y_label = "K0 = σ′h / σ′v";
  c.x_log = true;
  c.series.push_back(branch("loading, K0 = " + fmt("%.3f", s.k0_nc), s, true, k0));
  if (s.cs_points > 0) c.series.push_back(branch("unloading", s, false, k0));
  if (s.jaky_k0 > 0 && !s.steps.empty()) {
    plot::Series jaky;
    jaky.label = "Jaky 1 − sin φ′ (φ′ = " + fmt("%.1f", s.jaky_friction_angle) + "°)";
    jaky.dashed = true;
    double lo = 1e300, hi = 0;
    for (const OedometerStep& st : s.steps) {
      lo = std::min(lo, st.sigma_top * 1e-3);
      hi = std::max(hi, st.sigma_top * 1e-3);
    }
    jaky.x = {lo, hi};
    jaky.y = {s.jaky_k0, s.jaky_k0};
    c.series.push_back(jaky);
  }
  if (s.mayne_kulhawy_friction_angle > 0) {
    plot::Series mk;  // on the unloading steps, from the largest one
    mk.label = "Mayne & Kulhawy K0,nc OCR^sin φ′ (φ′ = " +
               fmt("%.1f", s.mayne_kulhawy_friction_angle) + "°)";
    mk.dashed = true;
    bool unloading = false;
    for (size_t i = 0; i < s.steps.size(); ++i) {
      const OedometerStep& st = s.steps[i];
      const bool last_loading = st.loading && (i + 1 == s.steps.size() || !s.steps[i + 1].loading);
      if (!last_loading && !unloading) continue;
      unloading = true;
      mk.x.push_back(st.sigma_top * 1e-3);
      mk.y.push_back(st.loading ? s.k0_nc : st.mayne_kulhawy_k0);
    }
    c.series.push_back(mk);
  }
  c.y_min = 0;
  plot::write_chart_png(c, (d / "k0.png").string());
}

void settlement(const std::filesystem::path& d, const std::string& title,
                const std::vector<OedometerRow>& rows, const OedometerSummary& s) {
  plot::Chart c;
  c.title = title + ": settlement";
  c.x_label = "Time (ms)";
  c.y_label = "Vertical strain εv (%)";
  plot::Series strain;
  strain.label = "εv from the first step's end";
  const double e0 = s.seated_void_ratio;
  for (const OedometerRow& r : rows) {
    strain.x.push_back(r.time * 1e3);
    strain.y.push_back(100 * (e0 - r.void_ratio) / (1 + e0));
  }
  c.series.push_back(strain);
  c.legend = false;
  plot::write_chart_png(c, (d / "settlement.png").string());
}

}  // namespace

void write_oedometer_plots(const std::string& dir, const std::string& title,
                           const std::vector<OedometerRow>& rows, const OedometerSummary& s) {
  const std::filesystem::path d = dir;
  e_log_sigma(d, title, rows, s);
  k0_plot(d, title, s);
  settlement(d, title, rows, s);
}

}  // namespace simsols
