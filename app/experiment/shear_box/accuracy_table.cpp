#include "app/experiment/shear_box/accuracy_table.h"

#include "solver/common/csv_table.h"

#include <cmath>
#include <map>
#include <sstream>

#include "solver/common/errors.h"

#include "solver/io/output.h"

namespace simsols {

const char* embedded_accuracy_csv();  // accuracy_csv.cpp (generated)
const char* embedded_profiles_csv();  // the same

const std::vector<SettingSummary>& accuracy_table() {
  static const std::vector<SettingSummary> table = parse_ensemble_csv(embedded_accuracy_csv());
  return table;
}

namespace {

// The setting of `specimen` with the knob `knob`, or null.
const SettingSummary* find_setting(StudySpecimen specimen, const char* knob) {
  for (const SettingSummary& e : accuracy_table())
    if (e.settings.specimen == specimen && e.settings.knob == knob) return &e;
  return nullptr;
}

std::string error_text(const char* name, const Interval& e) {
  std::string text = std::string(name) + " " + format_number("%+.2f", e.mean);
  if (std::isfinite(e.half_width)) text += " +- " + format_number("%.2f", e.half_width);
  return text + (e.significant() ? " deg (significant)" : " deg");
}

}  // namespace

const SettingSummary* expected_accuracy(double dt, Precision p, StudySpecimen specimen) {
  const std::vector<SettingSummary>& t = accuracy_table();
  const SettingSummary* baseline = find_setting(specimen, "baseline");
  const double baseline_i = baseline ? baseline->settings.inertial_number : 8e-4;
  const SettingSummary* best = nullptr;
  double best_d = 1e300;
  for (const SettingSummary& e : t) {
    if (e.settings.specimen != specimen || e.settings.precision != p ||
        e.settings.stiffness_scale != 1 ||
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
  const std::string where = " (" + std::string(specimen_name(s.settings.specimen)) +
                            " specimen, setting '" + s.settings.label + "', docs/accuracy.md)";
  if (!s.peak_error) return "accuracy study: " + (s.failure.empty() ? "no result" : s.failure) + where;
  std::string text = "expected (accuracy study, " + std::to_string(s.peak.n) +
                     " specimens) against the most accurate settings: " +
                     error_text("phi_peak", *s.peak_error);
  if (s.settings.specimen == StudySpecimen::Poured && s.residual_error)
    text += ", " + error_text("phi_res", *s.residual_error);
  const SettingSummary* ref = find_setting(s.settings.specimen, "reference");
  if (ref && ref->wall_seconds > 0)
    text += ", " + format_number("%.2f", s.wall_seconds / ref->wall_seconds) + "x their time";
  return text + where;
}

namespace {

// The rows of the embedded profiles.csv ('#' lines are its notes), each
// as column name -> cell.
std::vector<std::map<std::string, std::string>> profile_rows() {
  const CsvTable t = parse_csv(embedded_profiles_csv(), "profiles.csv");
  std::vector<std::map<std::string, std::string>> rows;
  for (const std::vector<std::string>& cells : t.rows) {
    auto& row = rows.emplace_back();
    for (size_t i = 0; i < cells.size(); ++i) row[t.header[i]] = cells[i];
  }
  return rows;
}

}  // namespace

std::string profile_accuracy_text(const std::string& profile, StudySpecimen specimen) {
  static const auto rows = profile_rows();
  for (const auto& r : rows) {
    if (r.at("profile") != profile || r.at("specimen") != specimen_name(specimen)) continue;
    const auto pm = [&](const char* name, const char* key) {
      return std::string(name) + " " + r.at(std::string(key) + "_deg") + " +- " +
             r.at(std::string(key) + "_ci95") + " deg";
    };
    return "measured against the paper profile on the same " + r.at("tests") + " " +
           specimen_name(specimen) + " specimens: " + pm("phi_peak", "peak_diff") + ", " +
           pm("phi_res", "residual_diff") + ", " + r.at("step_ratio") +
           "x fewer steps (docs/accuracy.md, the fast profile)";
  }
  return {};
}

std::optional<StudySpecimen> accuracy_study_specimen(const Scene& scene) {
  const ShearBox* box = scene.apparatus_as<ShearBox>();
  if (!box) return std::nullopt;
  return box->specimen.method == Specimen::Method::Layers ? StudySpecimen::Layered
                                                          : StudySpecimen::Poured;
}

}  // namespace simsols
