#include "study_ensemble.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "output.h"

namespace simsols {
namespace {

constexpr const char* kTwinKnob = "round-off";

struct Samples {
  std::vector<double> peak, residual, dilatancy;
  double wall = 0;
};

Samples samples_of(const std::vector<StudyCase>& runs, const StudySettings& s) {
  Samples x;
  for (const StudyCase& c : runs) {
    if (!c.settings.same_setting(s) || !c.shear.ok) continue;
    x.peak.push_back(c.shear.peak_angle);
    x.residual.push_back(c.shear.residual_angle);
    x.dilatancy.push_back(c.shear.dilatancy_angle);
    x.wall += c.shear.wall_seconds;
  }
  if (!x.peak.empty()) x.wall /= static_cast<double>(x.peak.size());
  return x;
}

const StudyCase* find_run(const std::vector<StudyCase>& runs, const char* knob, int seed) {
  for (const StudyCase& c : runs)
    if (c.settings.knob == knob && c.settings.seed == seed) return &c;
  return nullptr;
}

}  // namespace

std::vector<SettingSummary> summarise_settings(const std::vector<StudyCase>& runs) {
  std::vector<SettingSummary> out;
  for (const StudyCase& c : runs) {
    if (c.settings.knob == kTwinKnob) continue;
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const SettingSummary& s) { return s.settings.same_setting(c.settings); });
    if (it == out.end()) {
      out.push_back({});
      it = out.end() - 1;
      it->settings = c.settings;
      it->contact = c.contact;
    }
    ++it->runs;
    if (!c.shear.ok && it->failed++ == 0) it->failure = c.shear.failure;
  }
  if (out.empty()) return out;
  const Samples ref = samples_of(runs, out[0].settings);
  for (SettingSummary& s : out) {
    const Samples x = samples_of(runs, s.settings);
    if (x.peak.empty()) continue;
    s.peak = mean_ci95(x.peak);
    s.residual = mean_ci95(x.residual);
    s.dilatancy = mean_ci95(x.dilatancy);
    s.wall_seconds = x.wall;
    if (ref.peak.empty()) continue;
    s.peak_error = difference_ci95(x.peak, ref.peak);
    s.residual_error = difference_ci95(x.residual, ref.residual);
    s.dilatancy_error = difference_ci95(x.dilatancy, ref.dilatancy);
  }
  return out;
}

std::optional<double> separation_mm(const ShearResult& a, const ShearResult& b, double threshold) {
  const size_t n = std::min(a.curve_ratio.size(), b.curve_ratio.size());
  for (size_t i = 0; i < n; ++i)
    if (std::fabs(a.curve_ratio[i] - b.curve_ratio[i]) > threshold) return a.curve_mm[i];
  return std::nullopt;
}

Chaos measure_chaos(const std::vector<StudyCase>& runs) {
  Chaos c;
  if (runs.empty()) return c;
  const StudyCase* member = find_run(runs, runs[0].settings.knob.c_str(), 1);
  const StudyCase* twin = find_run(runs, kTwinKnob, 1);
  if (!member || !twin || !member->shear.ok || !twin->shear.ok) return c;
  const ShearResult &a = member->shear, &b = twin->shear;
  c.measured = true;
  c.separation = separation_mm(a, b);
  const size_t n = std::min(a.curve_ratio.size(), b.curve_ratio.size());
  for (size_t i = 0; i < n; ++i)
    c.largest_difference = std::max(c.largest_difference, std::fabs(a.curve_ratio[i] - b.curve_ratio[i]));
  c.peak_difference = b.peak_angle - a.peak_angle;
  c.residual_difference = b.residual_angle - a.residual_angle;
  c.dilatancy_difference = b.dilatancy_angle - a.dilatancy_angle;
  return c;
}

namespace {

// "mean,half_width" ("mean," when the interval is unknown)
std::string pair(const Interval& i) {
  return format_number("%.6g", i.mean) + "," +
         (std::isfinite(i.half_width) ? format_number("%.6g", i.half_width) : std::string());
}

std::string error_cells(const std::optional<Interval>& e) {
  if (!e) return ",,";
  return pair(*e) + "," + (e->significant() ? "yes" : "no");
}

}  // namespace

namespace {

// A row's field by column name.
class Columns {
 public:
  explicit Columns(const std::string& header) : names_(split_csv_line(header)) {}
  size_t at(const std::string& name) const {
    for (size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == name) return i;
    throw std::runtime_error("ensemble.csv has no column '" + name + "'");
  }

 private:
  std::vector<std::string> names_;
};

double number(const std::string& field, const std::string& what) {
  if (field.empty()) return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (end == field.c_str() || *end != '\0')
    throw std::runtime_error("ensemble.csv: '" + field + "' is not a number (" + what + ")");
  return v;
}

Interval interval(const std::vector<std::string>& f, size_t mean, size_t half, int n) {
  Interval i;
  i.mean = number(f[mean], "mean");
  i.half_width = number(f[half], "half width");
  i.n = n;
  return i;
}

}  // namespace

std::vector<SettingSummary> parse_ensemble_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("ensemble.csv is empty");
  const Columns c(line);
  const size_t knob = c.at("knob"), label = c.at("label"), dt = c.at("dt_fraction"),
               precision = c.at("precision"), stiffness = c.at("stiffness_scale"),
               inertial = c.at("inertial_number"), runs = c.at("runs"), failed = c.at("failed"),
               wall = c.at("wall_s_per_run"), failure = c.at("failure");
  const char* names[3] = {"peak", "residual", "dilatancy"};
  std::vector<SettingSummary> out;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (f.size() <= failure) throw std::runtime_error("ensemble.csv: a short row: " + line);
    SettingSummary s;
    s.settings.knob = f[knob];
    s.settings.label = f[label];
    s.settings.dt_fraction = number(f[dt], "dt_fraction");
    s.settings.precision = f[precision] == "double" ? Precision::Double : Precision::Float;
    s.settings.stiffness_scale = number(f[stiffness], "stiffness_scale");
    s.settings.inertial_number = number(f[inertial], "inertial_number");
    s.runs = static_cast<int>(number(f[runs], "runs"));
    s.failed = static_cast<int>(number(f[failed], "failed"));
    s.failure = f[failure];
    const int ok = s.runs - s.failed;
    if (!f[c.at("peak_deg")].empty()) {
      Interval* value[3] = {&s.peak, &s.residual, &s.dilatancy};
      std::optional<Interval>* error[3] = {&s.peak_error, &s.residual_error, &s.dilatancy_error};
      for (int k = 0; k < 3; ++k) {
        const std::string n = names[k];
        *value[k] = interval(f, c.at(n + "_deg"), c.at(n + "_ci95_deg"), ok);
        if (!f[c.at(n + "_err_deg")].empty())
          *error[k] = interval(f, c.at(n + "_err_deg"), c.at(n + "_err_ci95_deg"), ok);
      }
      s.wall_seconds = number(f[wall], "wall_s_per_run");
    }
    out.push_back(s);
  }
  return out;
}

std::string csv_quoted(std::string s) {
  for (char& ch : s)
    if (ch == '"') ch = '\'';
  return "\"" + s + "\"";
}

std::string settings_csv_cells(const StudySettings& k) {
  const auto num = [](double v) { return format_number("%.6g", v); };
  return csv_quoted(k.knob) + "," + csv_quoted(k.label) + "," + num(k.dt_fraction) + "," +
         (k.precision == Precision::Float ? "float" : "double") + "," + num(k.stiffness_scale) +
         "," + num(k.inertial_number) + "," + num(k.skin_factor) + "," + (k.rolling ? "1" : "0") +
         "," + (k.damping ? "1" : "0");
}

std::string ensemble_csv(const std::vector<SettingSummary>& settings) {
  std::string o = std::string(kSettingsCsvHeader) +
      ",runs,failed,peak_deg,peak_ci95_deg,residual_deg,residual_ci95_deg,dilatancy_deg,"
      "dilatancy_ci95_deg,peak_err_deg,peak_err_ci95_deg,peak_err_significant,residual_err_deg,"
      "residual_err_ci95_deg,residual_err_significant,dilatancy_err_deg,dilatancy_err_ci95_deg,"
      "dilatancy_err_significant,wall_s_per_run,failure\n";
  for (const SettingSummary& s : settings) {
    o += settings_csv_cells(s.settings) + "," + std::to_string(s.runs) + "," +
         std::to_string(s.failed);
    if (s.peak.n > 0)
      o += "," + pair(s.peak) + "," + pair(s.residual) + "," + pair(s.dilatancy) + "," +
           error_cells(s.peak_error) + "," + error_cells(s.residual_error) + "," +
           error_cells(s.dilatancy_error) + "," + format_number("%.2f", s.wall_seconds);
    else
      o += ",,,,,,,,,,,,,,,,";
    o += "," + csv_quoted(s.failure) + "\n";
  }
  return o;
}

namespace {

// "35.16 ± 0.05" ("35.16" for one run)
std::string pm(const Interval& i, const char* f = "%.2f") {
  return format_number(f, i.mean) +
         (std::isfinite(i.half_width) ? " ± " + format_number(f, i.half_width) : std::string());
}

// "+0.12 ± 0.30" with a bold mark when significant; "–" without one
std::string err(const std::optional<Interval>& e) {
  if (!e) return "–";
  const std::string t = (e->mean >= 0 ? "+" : "") + pm(*e);
  return e->significant() ? "**" + t + "**" : t;
}

}  // namespace

std::string ensemble_table_md(const std::vector<SettingSummary>& settings) {
  std::string md;
  const double ref_wall = settings.empty() ? 0 : settings[0].wall_seconds;
  md += "| setting | runs | φ_peak (°) | error (°) | φ_res (°) | error (°) | ψ_max (°) | "
        "error (°) | wall per run (s) | × ref |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const SettingSummary& s : settings) {
    md += "| " + s.settings.label + " | " + std::to_string(s.runs - s.failed) + "/" +
          std::to_string(s.runs) + " | ";
    if (s.peak.n == 0) {
      md += "failed: " + s.failure + " | | | | | | | |\n";
      continue;
    }
    md += pm(s.peak) + " | " + err(s.peak_error) + " | " + pm(s.residual) + " | " +
          err(s.residual_error) + " | " + pm(s.dilatancy) + " | " + err(s.dilatancy_error) + " | " +
          format_number("%.1f", s.wall_seconds) + " | " +
          (ref_wall > 0 ? format_number("%.2f", s.wall_seconds / ref_wall) : std::string("–")) +
          " |\n";
  }
  return md;
}

namespace {

void chaos_text(std::string& md, const Chaos& c) {
  md += "\n## Chaos\n\n";
  if (!c.measured) {
    md += "Not measured (the reference's first member and its round-off twin did not both run).\n";
    return;
  }
  md += "The reference's first member and its round-off twin, one bead moved by " +
        format_number("%g", kRoundOffPerturbation) + " d: τ/σ ";
  md += c.separation ? "first differs by more than " + format_number("%g", kSeparationThreshold) +
                           " at " + format_number("%.2f", *c.separation) + " mm of shear"
                     : "never differs by more than " + format_number("%g", kSeparationThreshold);
  md += " (largest difference " + format_number("%.3f", c.largest_difference) + "); φ_peak " +
        format_number("%+.2f", c.peak_difference) + "°, φ_res " +
        format_number("%+.2f", c.residual_difference) + "°, ψ_max " +
        format_number("%+.2f", c.dilatancy_difference) + "° apart.\n";
}

}  // namespace

std::string ensemble_summary_md(const StudyPreset& preset,
                                const std::vector<SettingSummary>& settings, const Chaos& chaos) {
  std::string md = "# Accuracy study `" + preset.name + "`\n\nShear test: " +
                   format_number("%g", preset.diameter_mm) + " mm beads, " +
                   format_number("%g", preset.stress_kpa) + " kPa, " +
                   format_number("%g", preset.displacement_mm) + " mm of shear, " +
                   std::to_string(preset.rows) + " rows; " + std::to_string(preset.ensemble) +
                   " specimens per setting (preparation seeds 1.." +
                   std::to_string(preset.ensemble) +
                   "). Each result is the ensemble mean ± its 95 % confidence interval; "
                   "an error is the difference from the reference's mean (first row) ± "
                   "Welch's 95 % interval, **bold** when significant (the interval excludes "
                   "zero).\n\n";
  md += ensemble_table_md(settings);
  md += "\nContact checks against theory (%; the same for every member): overlap / force / "
        "contact time / restitution / time to roll\n\n| setting | errors (%) |\n| --- | --- |\n";
  for (const SettingSummary& s : settings) {
    const ContactErrors& c = s.contact;
    md += "| " + s.settings.label + " | " +
          (c.ok ? format_number("%.2g", c.overlap) + " / " + format_number("%.2g", c.force) +
                      " / " + format_number("%.2g", c.duration) + " / " +
                      format_number("%.2g", c.restitution) + " / " + format_number("%.2g", c.rolling)
                : "failed: " + c.failure) +
          " |\n";
  }
  chaos_text(md, chaos);
  md += "\n## Recommendation\n\n";
  for (double tol : {0.1, 0.5}) {
    const SettingSummary* cheapest = nullptr;
    for (size_t i = 1; i < settings.size(); ++i) {
      const SettingSummary& s = settings[i];
      if (!s.peak_error || !std::isfinite(s.peak_error->half_width) || s.failed > 0) continue;
      if (std::fabs(s.peak_error->mean) + s.peak_error->half_width > tol) continue;
      if (!cheapest || s.wall_seconds < cheapest->wall_seconds) cheapest = &s;
    }
    md += "- φ_peak within " + format_number("%g", tol) + "° of the reference (95 %): ";
    md += cheapest ? "**" + cheapest->settings.label + "**, " +
                         format_number("%.1f", cheapest->wall_seconds) + " s per run\n"
                   : "no setting of this study\n";
  }
  return md;
}

}  // namespace simsols
