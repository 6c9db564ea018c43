// The periodic cell's report of a run (apparatus_report.h): its plots and result lines.
#include "app/experiment/apparatus_report.h"
#include "app/experiment/periodic_cell/cell_plots.h"
#include "solver/apparatus/periodic_cell/cell_programme.h"

namespace simsols {
namespace {

void cell_plots(const std::string& dir, const std::string& title, const ApparatusProgramme& p) {
  const auto& cell = dynamic_cast<const CellProgramme&>(p);
  write_cell_plots(dir, title, cell.rows(), cell.summary());
}

std::string cell_text(const TestRun& run) {
  const auto& cell = dynamic_cast<const CellProgramme&>(*run.programme);
  const CellSummary s = cell.summary();
  std::string o = report_printf("periodic cell %s %s: p = %.0f kPa, I = %.3g, %d beads, %lld steps\n",
                                s.test.c_str(), run_state_word(run.state), s.pressure * 1e-3,
                                s.inertial_number, run.state.particles, run.state.steps);
  o += report_printf("  compressed: phi = %.4f, Z = %.3f\n", s.phi_compressed, s.z_compressed);
  if (s.ratio.rows == 0) return o;
  o += report_printf("  steady (strain >= %.3g, %d rows): stress ratio %.4f +- %.4f, mobilised angle "
                     "%.2f +- %.2f deg, phi %.4f +- %.4f, Z %.3f +- %.3f (95 %% intervals of one specimen)\n",
                     s.from, s.ratio.rows, s.ratio.mean, s.ratio.half_width, s.angle.mean, s.angle.half_width,
                     s.phi.mean, s.phi.half_width, s.z.mean, s.z.half_width);
  return o;
}

}  // namespace

const TestReport& periodic_cell_report() {
  static const TestReport r{"periodic_cell", cell_plots, cell_text};
  return r;
}

}  // namespace simsols
