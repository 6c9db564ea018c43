#include "app/experiment/shear_box/study_ensemble.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "solver/io/output.h"
#include "solver/scene/choices.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

struct Samples {
  std::vector<double> peak, residual, dilatancy;
  std::vector<int> seed;
  double wall = 0;
};

Samples samples_of(const std::vector<StudyCase>& runs, const StudySettings& s) {
  Samples x;
  for (const StudyCase& c : runs) {
    if (!c.settings.same_setting(s) || !c.shear.ok) continue;
    x.peak.push_back(c.shear.peak_angle);
    x.residual.push_back(c.shear.residual_angle);
    x.dilatancy.push_back(c.shear.dilatancy_angle);
    x.seed.push_back(c.settings.seed);
    x.wall += c.shear.wall_seconds;
  }
  if (!x.peak.empty()) x.wall /= static_cast<double>(x.peak.size());
  return x;
}

const StudyCase* find_run(const std::vector<StudyCase>& runs, StudySpecimen specimen,
                          const char* knob, int seed) {
  for (const StudyCase& c : runs)
    if (c.settings.specimen == specimen && c.settings.knob == knob && c.settings.seed == seed)
      return &c;
  return nullptr;
}

// The reference of `s`'s specimen: its setting with the knob "reference",
// else its first.
const SettingSummary* reference_of(const std::vector<SettingSummary>& all, const StudySettings& s) {
  const SettingSummary* first = nullptr;
  for (const SettingSummary& x : all) {
    if (x.settings.specimen != s.specimen) continue;
    if (x.settings.knob == "reference") return &x;
    if (!first) first = &x;
  }
  return first;
}

// The error of x against the reference on one result: the mean of the
// paired differences x_k - ref_k over the seeds k both ran, with Student's
// interval (the same specimen under both settings: the specimen-to-specimen
// scatter cancels); Welch's interval of the two means when fewer than two
// seeds pair up.
Interval error_of(const Samples& x, const Samples& ref, std::vector<double> Samples::*field) {
  std::vector<double> d;
  for (size_t i = 0; i < x.seed.size(); ++i)
    for (size_t j = 0; j < ref.seed.size(); ++j)
      if (x.seed[i] == ref.seed[j]) d.push_back((x.*field)[i] - (ref.*field)[j]);
  if (d.size() >= 2) return mean_ci95(d);
  return difference_ci95(x.*field, ref.*field);
}

}  // namespace

std::vector<SettingSummary> summarise_settings(const std::vector<StudyCase>& runs) {
  std::vector<SettingSummary> out;
  for (const StudyCase& c : runs) {
    if (c.settings.knob == kTwinKnob || c.settings.knob == kShearTwinKnob) continue;
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
  for (SettingSummary& s : out) {
    const Samples ref = samples_of(runs, reference_of(out, s.settings)->settings);
    const Samples x = samples_of(runs, s.settings);
    if (x.peak.empty()) continue;
    s.peak = mean_ci95(x.peak);
    s.residual = mean_ci95(x.residual);
    s.dilatancy = mean_ci95(x.dilatancy);
    s.wall_seconds = x.wall;
    if (ref.peak.empty()) continue;
    s.peak_error = error_of(x, ref, &Samples::peak);
    s.residual_error = error_of(x, ref, &Samples::residual);
    s.dilatancy_error = error_of(x, ref, &Samples::dilatancy);
  }
  return out;
}

std::vector<SettingSummary> settings_of(const std::vector<SettingSummary>& all,
                                        StudySpecimen specimen) {
  std::vector<SettingSummary> out;
  for (const SettingSummary& s : all)
    if (s.settings.specimen == specimen) out.push_back(s);
  return out;
}

std::optional<double> separation_mm(const ShearResult& a, const ShearResult& b, double threshold) {
  const size_t n = std::min(a.curve_ratio.size(), b.curve_ratio.size());
  for (size_t i = 0; i < n; ++i)
    if (std::fabs(a.curve_ratio[i] - b.curve_ratio[i]) > threshold) return a.curve_mm[i];
  return std::nullopt;
}

Chaos measure_chaos(const std::vector<StudyCase>& runs, StudySpecimen specimen,
                    const char* twin_knob) {
  Chaos c;
  const StudyCase* member = find_run(runs, specimen, "reference", 1);
  const StudyCase* twin = find_run(runs, specimen, twin_knob, 1);
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
    throw ReadError("ensemble.csv has no column '" + name + "'");
  }

 private:
  std::vector<std::string> names_;
};

double number(const std::string& field, const std::string& what) {
  if (field.empty()) return std::numeric_limits<double>::quiet_NaN();
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (end == field.c_str() || *end != '\0')
    throw ReadError("ensemble.csv: '" + field + "' is not a number (" + what + ")");
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
  if (!std::getline(in, line)) throw ReadError("ensemble.csv is empty");
  const Columns c(line);
  const size_t specimen = c.at("specimen"), knob = c.at("knob"), label = c.at("label"), dt = c.at("dt_fraction"),
               precision = c.at("precision"), stiffness = c.at("stiffness_scale"),
               inertial = c.at("inertial_number"), runs = c.at("runs"), failed = c.at("failed"),
               wall = c.at("wall_s_per_run"), failure = c.at("failure");
  const char* names[3] = {"peak", "residual", "dilatancy"};
  std::vector<SettingSummary> out;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (f.size() <= failure) throw ReadError("ensemble.csv: a short row: " + line);
    SettingSummary s;
    const std::optional<StudySpecimen> kind = parse_specimen(f[specimen]);
    if (!kind)
      throw ReadError("ensemble.csv: specimen '" + f[specimen] +
                               "' is not one of: layered, poured");
    s.settings.specimen = *kind;
    s.settings.knob = f[knob];
    s.settings.label = f[label];
    s.settings.dt_fraction = number(f[dt], "dt_fraction");
    s.settings.precision = parse_choice<Precision>(f[precision]).value_or(Precision::Float);
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
  return std::string(specimen_name(k.specimen)) + "," + csv_quoted(k.knob) + "," +
         csv_quoted(k.label) + "," + num(k.dt_fraction) + "," +
         choice_name(k.precision) + "," + num(k.stiffness_scale) +
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

std::string ensemble_table_md(const std::vector<SettingSummary>& all, StudySpecimen specimen) {
  const std::vector<SettingSummary> settings = settings_of(all, specimen);
  std::string md;
  const double ref_wall = settings.empty() ? 0 : reference_of(all, settings[0].settings)->wall_seconds;
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

// One twin's line: `when` says when its bead was moved.
void chaos_line(std::string& md, const Chaos& c, const char* when) {
  if (!c.measured) {
    md += std::string("- Moved ") + when +
          ": not measured (the reference's first member and this round-off twin did not both "
          "run).\n";
    return;
  }
  md += std::string("- Moved ") + when + ": τ/σ ";
  md += c.separation ? "first differs by more than " + format_number("%g", kSeparationThreshold) +
                           " at " + format_number("%.2f", *c.separation) + " mm of shear"
                     : "never differs by more than " + format_number("%g", kSeparationThreshold);
  md += " (largest difference " + format_number("%.3f", c.largest_difference) + "); φ_peak " +
        format_number("%+.2f", c.peak_difference) + "°, φ_res " +
        format_number("%+.2f", c.residual_difference) + "°, ψ_max " +
        format_number("%+.2f", c.dilatancy_difference) + "° apart.\n";
}

void chaos_text(std::string& md, const std::vector<StudyCase>& runs, StudySpecimen specimen) {
  md += "\n### Chaos\n\nThe reference's first member against its round-off twin, one bead moved by " +
        format_number("%g", kRoundOffPerturbation) + " d:\n\n";
  chaos_line(md, measure_chaos(runs, specimen, kTwinKnob), "before the preparation");
  if (specimen == StudySpecimen::Poured)
    chaos_line(md, measure_chaos(runs, specimen, kShearTwinKnob), "as shearing starts");
}

}  // namespace

namespace {

void contact_table(std::string& md, const std::vector<SettingSummary>& settings) {
  md += "\nContact checks against theory (%; no specimen, so the same for every member and both "
        "specimens): overlap / force / contact time / restitution / time to roll\n\n"
        "| setting | errors (%) |\n| --- | --- |\n";
  std::vector<std::string> listed;
  for (const SettingSummary& s : settings) {
    if (std::find(listed.begin(), listed.end(), s.settings.label) != listed.end()) continue;
    listed.push_back(s.settings.label);
    const ContactErrors& c = s.contact;
    md += "| " + s.settings.label + " | " +
          (c.ok ? format_number("%.2g", c.overlap) + " / " + format_number("%.2g", c.force) +
                      " / " + format_number("%.2g", c.duration) + " / " +
                      format_number("%.2g", c.restitution) + " / " + format_number("%.2g", c.rolling)
                : "failed: " + c.failure) +
          " |\n";
  }
}

// The cheapest setting of `specimen` whose error on `which` (peak,
// residual or dilatancy) is within `tol` degrees at 95 %, or null.
const SettingSummary* cheapest_within(const std::vector<SettingSummary>& settings,
                                      StudySpecimen specimen,
                                      std::optional<Interval> SettingSummary::*which, double tol) {
  const SettingSummary* best = nullptr;
  for (const SettingSummary& s : settings) {
    const std::optional<Interval>& e = s.*which;
    if (s.settings.specimen != specimen || s.settings.knob == "reference" || !e ||
        !std::isfinite(e->half_width) || s.failed > 0)
      continue;
    if (std::fabs(e->mean) + e->half_width > tol) continue;
    if (!best || s.wall_seconds < best->wall_seconds) best = &s;
  }
  return best;
}

void recommendation(std::string& md, const std::vector<SettingSummary>& settings,
                    StudySpecimen specimen) {
  md += "\n### Recommendation\n\n";
  const struct {
    const char* name;
    std::optional<Interval> SettingSummary::*which;
  } results[] = {{"φ_peak", &SettingSummary::peak_error},
                 {"φ_res", &SettingSummary::residual_error},
                 {"ψ_max", &SettingSummary::dilatancy_error}};
  for (const auto& r : results)
    for (double tol : {0.5, 2.0}) {
      const SettingSummary* s = cheapest_within(settings, specimen, r.which, tol);
      md += std::string("- ") + r.name + " within " + format_number("%g", tol) +
            "° of the reference (95 %): ";
      md += s ? "**" + s->settings.label + "**, " + format_number("%.1f", s->wall_seconds) +
                    " s per run\n"
              : "no setting of this study\n";
    }
}

}  // namespace

std::string specimen_description(const StudyPreset& preset, StudySpecimen specimen) {
  if (specimen == StudySpecimen::Layered)
    return "the paper's layered specimen (" +
           (preset.layers > 0 ? std::to_string(preset.layers) : std::string("Table 1's")) +
           " layers, each shifted by its seed) in the paper's 60.23 × 60.07 mm box";
  return "a poured (random) specimen in a box " + format_number("%g", preset.poured_box_scale) +
         " × the paper's, length and width (" + format_number("%.1f", 60.23 * preset.poured_box_scale) +
         " × " + format_number("%.1f", 60.07 * preset.poured_box_scale) +
         " mm), the beads of " + (preset.layers > 0 ? std::to_string(preset.layers) : std::string("4")) +
         " layers rained in and settled for up to " + format_number("%g", preset.poured_settle_time) + " s";
}

std::string ensemble_summary_md(const StudyPreset& preset,
                                const std::vector<SettingSummary>& settings,
                                const std::vector<StudyCase>& runs) {
  std::string md = "# Accuracy study `" + preset.name + "`\n\nShear test: " +
                   format_number("%g", preset.diameter_mm) + " mm beads, " +
                   format_number("%g", preset.stress_kpa) + " kPa, " +
                   format_number("%g", preset.displacement_mm) + " mm of shear, " +
                   std::to_string(preset.rows) + " rows; " + std::to_string(preset.ensemble) +
                   " specimens per setting (preparation seeds 1.." +
                   std::to_string(preset.ensemble) +
                   "). Each result is the ensemble mean ± its 95 % confidence interval; "
                   "an error is the mean of the paired differences from the specimen's reference "
                   "(its first row), member by member on the same seeds, ± its 95 % Student "
                   "interval, **bold** when significant (the interval excludes zero).\n";
  for (StudySpecimen specimen : kStudySpecimens) {
    if (settings_of(settings, specimen).empty()) continue;
    md += "\n## The " + std::string(specimen_name(specimen)) + " specimen\n\nSpecimen: " +
          specimen_description(preset, specimen) + ".\n\n" + ensemble_table_md(settings, specimen);
    chaos_text(md, runs, specimen);
    recommendation(md, settings, specimen);
  }
  contact_table(md, settings);
  return md;
}

}  // namespace simsols
