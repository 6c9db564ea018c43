// The triaxial report of a run (apparatus_report.h): its plots and result lines.
#include "app/experiment/apparatus_report.h"
#include "app/experiment/triaxial/triaxial_plots.h"
#include "solver/apparatus/triaxial/triaxial_programme.h"

namespace simsols {
namespace {

std::string triaxial_text(const TestRun& run) {
  const auto r = typed_result<TriaxialProgramme>(run);
  const TriaxialSummary& s = r.summary;
  std::string o = report_printf("triaxial test %s: p'0 = %.0f kPa, %d beads, %lld steps in %.0f s\n",
                      run_state_word(r.state), s.confining_stress * 1e-3, r.state.particles, r.state.steps,
                      s.wall_seconds);
  if (r.rows.empty()) return o;
  o += report_printf("  peak     phi = %.2f deg  q/p' = %.3f at eps_a = %.2f %%\n", s.peak_angle,
           s.peak_q_over_p, 100 * s.peak_axial_strain);
  o += report_printf("  critical phi = %.2f deg  q/p' = %.3f  e = %.4f  p' = %.1f kPa (last 20 %%)\n",
           s.critical_angle, s.critical_q_over_p, s.critical_void_ratio, s.critical_p * 1e-3);
  o += report_printf("  max dilatancy angle %.2f deg; walls vs internal stress within %.2f %% of p'; "
           "inertial number <= %.2g\n",
           s.max_dilatancy_angle, 100 * s.wall_internal_gap, s.max_inertial_number);
  return o;
}

}  // namespace

const TestReport& triaxial_report() {
  static const TestReport r{"triaxial", programme_plots<TriaxialProgramme, write_triaxial_plots>, triaxial_text};
  return r;
}

}  // namespace simsols
