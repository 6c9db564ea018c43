// The shear_box report of a run (apparatus_report.h): its plots and result lines.
#include "app/experiment/apparatus_report.h"
#include "app/experiment/shear_box/shear_plots.h"
#include "solver/apparatus/shear_box/shear_programme.h"

namespace simsols {
namespace {

std::string shear_text(const TestRun& run) {
  const auto r = typed_result<ShearProgramme>(run);
  const ShearSummary& s = r.summary;
  std::string o = report_printf("shear test %s: sigma = %.0f kPa, d = %.4g mm, %d beads, %lld steps in %.0f s\n",
                      run_state_word(r.state), s.normal_stress_target * 1e-3, s.bead_diameter * 1e3,
                      r.state.particles, r.state.steps, s.wall_seconds);
  if (r.rows.empty())
    return o + report_printf("  nothing measured yet: stopped before shearing began (step %lld)\n", r.state.steps);
  o += report_printf("  peak     tau/sigma = %.3f  phi_peak     = %.2f deg  (tau = %.2f kPa at %.2f mm; the "
           "first peak)\n",
           s.peak_ratio, s.peak_angle, s.peak_tau * 1e-3, s.peak_displacement * 1e3);
  if (s.critical_state)
    o += report_printf("  residual tau/sigma = %.3f  phi_residual = %.2f deg  (tau = %.2f kPa, at the "
                       "critical state from %.2f mm: dz/dx = %+.3f)\n",
                       s.residual_ratio, s.residual_angle, s.residual_tau * 1e-3,
                       s.residual_from * 1e3, s.residual_dilation_rate);
  else
    o += report_printf("  residual tau/sigma = %.3f  phi_residual = %.2f deg  (tau = %.2f kPa, the last "
                       "20 %%; no critical state: dz/dx = %+.3f there)\n",
                       s.residual_ratio, s.residual_angle, s.residual_tau * 1e-3,
                       s.residual_dilation_rate);
  if (s.max_ratio > s.peak_ratio)
    o += report_printf("  largest  tau/sigma = %.3f  (phi = %.2f deg at %.2f mm, after the peak)\n",
             s.max_ratio, s.max_angle, s.max_displacement * 1e3);
  if (s.dynamic_events > 0)
    o += report_printf("  dynamic events %d (Taylor: tau/sigma - dz/dx down to %.3f at %.2f mm)%s\n",
                       s.dynamic_events, s.taylor_min, s.taylor_min_displacement * 1e3,
                       s.max_dilatancy_dynamic ? "; the steepest dilatancy is one" : "");
  o += report_printf("  max dilatancy angle %.2f deg; inertial number <= %.2g; beads outside %d\n"
           "  sigma band %+.2f%% / %+.2f%% (RMS %.2f%%)%s; tau/sigma at rest %.3f\n",
           s.max_dilatancy_angle, s.max_inertial_number, s.max_outside, 100 * s.sigma_band_lo,
           100 * s.sigma_band_hi, 100 * s.sigma_rms,
           s.valid ? "" : " INVALID: the load was not held within +-10 %", s.start_ratio);
  if (!r.state.finished)
    o += report_printf("  (so far: %zu of the test's rows, at %.2f mm)\n", r.rows.size(),
             r.rows.back().displacement * 1e3);
  return o;
}

}  // namespace

const TestReport& shear_box_report() {
  static const TestReport r{"shear_box", programme_plots<ShearProgramme, write_shear_plots>, shear_text};
  return r;
}

}  // namespace simsols
