#include "app/experiment/periodic_cell/cell_plots.h"

#include "render/plot/chart.h"

namespace simsols {
namespace {

void one_plot(const std::string& path, const std::string& title, const std::string& x_label,
              const std::string& y_label, const std::vector<CellRow>& rows, int column,
              const SteadyValue& steady, double from) {
  plot::Chart c;
  c.title = title;
  c.x_label = x_label;
  c.y_label = y_label;
  plot::Series s;
  s.label = "measured (mean of each row's controls)";
  for (const CellRow& r : rows)
    if (r[kColStage] == 1) s.x.push_back(r[kColStrain]), s.y.push_back(r[column]);
  if (s.x.empty()) return;
  c.series.push_back(s);
  plot::Series m;
  m.label = "steady mean";
  m.dashed = true;
  m.x = {from, s.x.back()};
  m.y = {steady.mean, steady.mean};
  c.series.push_back(m);
  plot::write_chart_png(c, path);
}

}  // namespace

void write_cell_plots(const std::string& dir, const std::string& title, const std::vector<CellRow>& rows,
                      const CellSummary& s) {
  const bool shear = s.test == "simple_shear";
  const std::string x = shear ? "shear strain γ" : "axial strain ε_zz";
  one_plot(dir + "/cell_ratio.png", title, x, shear ? "τ / σ_zz" : "q / p", rows, kColRatio, s.ratio, s.from);
  one_plot(dir + "/cell_solid_fraction.png", title, x, "solid fraction Φ", rows, kColPhi, s.phi, s.from);
  one_plot(dir + "/cell_coordination.png", title, x, "coordination Z", rows, kColZ, s.z, s.from);
}

}  // namespace simsols
