#include "app/experiment/apparatus_report.h"

#include <cstdarg>
#include <cstdio>
#include <stdexcept>

#include "app/experiment/oedometer_plots.h"
#include "app/experiment/shear_plots.h"
#include "app/experiment/triaxial_plots.h"
#include "solver/apparatus/oedometer/oedometer_programme.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "solver/apparatus/triaxial/triaxial_programme.h"

namespace simsols {
namespace {

// A kind's plots (shear_plots.h, ...) of its programme's rows and summary.
template <class Programme, auto write>
void plots(const std::string& dir, const std::string& title, const ApparatusProgramme& p) {
  const auto& programme = dynamic_cast<const Programme&>(p);
  write(dir, title, programme.rows(), programme.summary());
}

// printf into a string.
std::string say(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string say(const char* format, ...) {
  char buf[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

const char* how(const ProgrammeRunState& s) {
  return s.finished ? "finished" : s.interrupted ? "interrupted" : "stopped";
}

std::string shear_text(const TestRun& run) {
  const auto r = typed_result<ShearProgramme>(run);
  const ShearSummary& s = r.summary;
  std::string o = say("shear test %s: sigma = %.0f kPa, d = %.4g mm, %d beads, %lld steps in %.0f s\n",
                      how(r.state), s.normal_stress_target * 1e-3, s.bead_diameter * 1e3,
                      r.state.particles, r.state.steps, s.wall_seconds);
  if (r.rows.empty())
    return o + say("  nothing measured yet: stopped before shearing began (step %lld)\n", r.state.steps);
  o += say("  peak     tau/sigma = %.3f  phi_peak     = %.2f deg  (tau = %.2f kPa at %.2f mm; the "
           "first peak)\n",
           s.peak_ratio, s.peak_angle, s.peak_tau * 1e-3, s.peak_displacement * 1e3);
  o += say("  residual tau/sigma = %.3f  phi_residual = %.2f deg  (tau = %.2f kPa, mean over the "
           "last 20 %%)\n",
           s.residual_ratio, s.residual_angle, s.residual_tau * 1e-3);
  if (s.max_ratio > s.peak_ratio)
    o += say("  largest  tau/sigma = %.3f  (phi = %.2f deg at %.2f mm, after the peak)\n",
             s.max_ratio, s.max_angle, s.max_displacement * 1e3);
  o += say("  max dilatancy angle %.2f deg; inertial number <= %.2g; beads outside %d\n"
           "  sigma band %+.2f%% / %+.2f%% (RMS %.2f%%)%s; tau/sigma at rest %.3f\n",
           s.max_dilatancy_angle, s.max_inertial_number, s.max_outside, 100 * s.sigma_band_lo,
           100 * s.sigma_band_hi, 100 * s.sigma_rms,
           s.valid ? "" : " INVALID: the load was not held within +-10 %", s.start_ratio);
  if (!r.state.finished)
    o += say("  (so far: %zu of the test's rows, at %.2f mm)\n", r.rows.size(),
             r.rows.back().displacement * 1e3);
  return o;
}

std::string oedometer_text(const TestRun& run) {
  const auto r = typed_result<OedometerProgramme>(run);
  const OedometerSummary& s = r.summary;
  std::string o = say("oedometer test %s: %zu of its load steps, %d beads, %lld steps in %.0f s\n",
                      how(r.state), s.steps.size(), r.state.particles, r.state.steps, s.wall_seconds);
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const OedometerStep& st = s.steps[i];
    o += say("  step %2zu  sigma'_v = %7.1f kPa  e = %.5f  eps_v = %7.4f %%  K0 = %.3f%s\n", i + 1,
             st.sigma_top * 1e-3, st.void_ratio, 100 * st.strain, st.k0,
             st.equilibrium ? "" : "  (held for step_time, not in equilibrium)");
  }
  if (!r.state.finished) return o;
  o += say("  Cc = %.4f (%d steps)  Cs = %.4f (%d steps)  K0 (NC) = %.3f  side friction %.1f %%\n",
           s.cc, s.cc_points, s.cs, s.cs_points, s.k0_nc, 100 * s.side_friction);
  if (s.jaky_k0 > 0)
    o += say("  Jaky 1 - sin(%.1f deg) = %.3f; the measured K0 implies phi' = %.1f deg\n",
             s.jaky_friction_angle, s.jaky_k0, s.implied_friction_angle);
  if (!s.valid) o += "  INVALID: a step ended at step_time, not in equilibrium\n";
  return o;
}

std::string triaxial_text(const TestRun& run) {
  const auto r = typed_result<TriaxialProgramme>(run);
  const TriaxialSummary& s = r.summary;
  std::string o = say("triaxial test %s: p'0 = %.0f kPa, %d beads, %lld steps in %.0f s\n",
                      how(r.state), s.confining_stress * 1e-3, r.state.particles, r.state.steps,
                      s.wall_seconds);
  if (r.rows.empty()) return o;
  o += say("  peak     phi = %.2f deg  q/p' = %.3f at eps_a = %.2f %%\n", s.peak_angle,
           s.peak_q_over_p, 100 * s.peak_axial_strain);
  o += say("  critical phi = %.2f deg  q/p' = %.3f  e = %.4f  p' = %.1f kPa (last 20 %%)\n",
           s.critical_angle, s.critical_q_over_p, s.critical_void_ratio, s.critical_p * 1e-3);
  o += say("  max dilatancy angle %.2f deg; walls vs internal stress within %.2f %% of p'; "
           "inertial number <= %.2g\n",
           s.max_dilatancy_angle, 100 * s.wall_internal_gap, s.max_inertial_number);
  return o;
}

struct TestReport {
  std::string_view kind;  // the registry's name
  void (*plots)(const std::string& dir, const std::string& title, const ApparatusProgramme& t);
  std::string (*text)(const TestRun& run);
};

constexpr TestReport kReports[] = {
    {"shear_box", plots<ShearProgramme, write_shear_plots>, shear_text},
    {"oedometer", plots<OedometerProgramme, write_oedometer_plots>, oedometer_text},
    {"triaxial", plots<TriaxialProgramme, write_triaxial_plots>, triaxial_text},
};

const TestReport* report_of(std::string_view kind) {
  return entry_for_kind<TestReport>(kReports, kind);
}

// A kind without a report of its own (an entry above is optional): its
// rows and summary.txt are written all the same; no plots, and this line.
std::string plain_text(const TestRun& run) {
  return std::string(run.kind->title) + " test " + (run.state.finished ? "finished" : "stopped") +
         ": " + std::to_string(run.state.particles) + " beads, " +
         std::to_string(run.state.steps) + " steps (its rows: " + run.programme->rows_file() + ")\n";
}

}  // namespace

bool has_test_report(std::string_view kind) { return report_of(kind) != nullptr; }

void write_test_plots(const std::string& dir, const std::string& title, const ApparatusKind& kind,
                      const ApparatusProgramme& test) {
  if (const TestReport* r = report_of(kind.name)) r->plots(dir, title, test);
}

std::string test_result_text(const TestRun& run, const std::string& dir) {
  const TestReport* report = report_of(run.kind->name);
  std::string o = report ? report->text(run) : plain_text(run);
  if (!run.state.stopped_after.empty())
    o += "  stopped at the end of the stage '" + run.state.stopped_after + "' (--stop-at)\n";
  o += "  results in " + dir + "\n";
  if (!run.state.finished) o += "  " + resume_hint(dir) + "\n";
  return o;
}

}  // namespace simsols
