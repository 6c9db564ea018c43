// The oedometer report of a run (apparatus_report.h): its plots and result lines.
#include "app/experiment/apparatus_report.h"
#include "app/experiment/oedometer/oedometer_plots.h"
#include "solver/apparatus/oedometer/oedometer_programme.h"

namespace simsols {
namespace {

std::string oedometer_text(const TestRun& run) {
  const auto r = typed_result<OedometerProgramme>(run);
  const OedometerSummary& s = r.summary;
  std::string o = report_printf("oedometer test %s: %zu of its load steps, %d beads, %lld steps in %.0f s\n",
                      run_state_word(r.state), s.steps.size(), r.state.particles, r.state.steps, s.wall_seconds);
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const OedometerStep& st = s.steps[i];
    o += report_printf("  step %2zu  sigma'_v = %7.1f kPa  e = %.5f  eps_v = %7.4f %%  K0 = %.3f%s\n", i + 1,
             st.sigma_top * 1e-3, st.void_ratio, 100 * st.strain, st.k0,
             st.equilibrium ? "" : "  (held for step_time, not in equilibrium)");
  }
  if (!r.state.finished) return o;
  o += report_printf("  Cc = %.4f (%d steps)  Cs = %.4f (%d steps)  K0 (NC) = %.3f  side friction %.1f %%\n",
           s.cc, s.cc_points, s.cs, s.cs_points, s.k0_nc, 100 * s.side_friction);
  if (s.jaky_k0 > 0)
    o += report_printf("  Jaky 1 - sin(%.1f deg) = %.3f; the measured K0 implies phi' = %.1f deg\n",
             s.jaky_friction_angle, s.jaky_k0, s.implied_friction_angle);
  if (s.cs_points > 0) {
    o += report_printf("  plastic share of the loading compression %.2f: %s\n", s.plastic_share,
                       s.virgin ? "a virgin compression line"
                                : "mostly elastic, Cc is no virgin compression index");
    if (s.mayne_kulhawy_friction_angle > 0)
      o += report_printf("  K0 on unloading against Mayne & Kulhawy K0_nc OCR^sin(%.1f deg): worst %.0f %%\n",
                         s.mayne_kulhawy_friction_angle, 100 * s.mayne_kulhawy_worst);
  }
  if (!s.valid) o += "  INVALID: a step ended at step_time, not in equilibrium\n";
  return o;
}

}  // namespace

const TestReport& oedometer_report() {
  static const TestReport r{"oedometer", programme_plots<OedometerProgramme, write_oedometer_plots>, oedometer_text};
  return r;
}

}  // namespace simsols
