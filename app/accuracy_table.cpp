#include "accuracy_table.h"

#include <cmath>

#include "output.h"

namespace simsols {

const char* embedded_accuracy_csv();  // accuracy_csv.cpp (generated)

const std::vector<SettingSummary>& accuracy_table() {
  static const std::vector<SettingSummary> table = parse_ensemble_csv(embedded_accuracy_csv());
  return table;
}

const SettingSummary* expected_accuracy(double dt, Precision p) {
  const std::vector<SettingSummary>& t = accuracy_table();
  const double baseline_i = t.size() > 1 ? t[1].settings.inertial_number : 8e-4;
  const SettingSummary* best = nullptr;
  double best_d = 1e300;
  for (const SettingSummary& e : t) {
    if (e.settings.precision != p || e.settings.stiffness_scale != 1 ||
        e.settings.inertial_number != baseline_i)
      continue;
    const double d = std::fabs(std::log(e.settings.dt_fraction / dt));
    if (d < best_d) {
      best_d = d;
      best = &e;
    }
  }
  return best;
}

std::string expected_accuracy_text(const SettingSummary& s) {
  const std::vector<SettingSummary>& t = accuracy_table();
  const std::string where = " (setting '" + s.settings.label + "', docs/accuracy.md)";
  if (!s.peak_error) return "accuracy study: " + (s.failure.empty() ? "no result" : s.failure) + where;
  const Interval& e = *s.peak_error;
  std::string text = "expected (accuracy study, " + std::to_string(s.peak.n) +
                     " specimens): phi_peak " + format_number("%+.2f", e.mean);
  if (std::isfinite(e.half_width)) text += " +- " + format_number("%.2f", e.half_width);
  text += " deg from the most accurate settings";
  text += e.significant() ? " (a significant difference)" : " (within the specimens' scatter)";
  if (!t.empty() && t[0].wall_seconds > 0)
    text += ", " + format_number("%.2f", s.wall_seconds / t[0].wall_seconds) + "x their time";
  return text + where;
}

}  // namespace simsols
