// The accuracy study's ensembles: what one setting gives over its members,
// and how far a run can be predicted at all.
//
// A setting runs as an ensemble of specimens that differ only in their
// preparation seed (study_runs in study.h). Its results are the ensemble
// means with their 95 % confidence intervals, and its error against the
// reference is paired: the mean of the differences member by member (the
// same seed, so the same specimen, under both settings) with Student's
// interval, which the specimen-to-specimen scatter does not widen (Welch's
// interval of the two means, study_stats.h, when fewer than two seeds
// pair up); significant only when that interval excludes zero.
//
// Each specimen (StudySpecimen) has its own reference, and its settings are
// compared with that one only.
//
// Chaos: a specimen's reference's seed-1 member and its round-off twin (one bead
// moved by 1e-9 d, before the preparation or, for the poured specimen,
// also as shearing starts) differ only at round-off. The displacement at which
// their tau/sigma curves first differ by more than kSeparationThreshold
// is where the test stops being predictable run by run; past it only the
// ensemble statistics are.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/experiment/shear_box/study.h"
#include "app/experiment/shear_box/study_stats.h"

namespace simsols {

constexpr double kSeparationThreshold = 0.02;  // in tau/sigma

struct SettingSummary {
  StudySettings settings;  // the first member's (seed 1)
  ContactErrors contact;   // the first member's: the contact checks have no specimen
  int runs = 0, failed = 0;
  std::string failure;     // the first failed member's reason
  Interval peak, residual, dilatancy;                          // deg
  std::optional<Interval> peak_error, residual_error, dilatancy_error;  // deg, vs the reference
  double wall_seconds = 0;  // mean per member
};

// One summary per setting and specimen, in the order of first appearance;
// errors against the specimen's reference (its knob "reference", else its
// first setting). Round-off twins are not a setting of their own.
std::vector<SettingSummary> summarise_settings(const std::vector<StudyCase>& runs);

// The summaries of `specimen`'s settings, in their order.
std::vector<SettingSummary> settings_of(const std::vector<SettingSummary>& all,
                                        StudySpecimen specimen);

// Where two runs' tau/sigma curves first differ by more than `threshold`
// (mm of shear), or nullopt when they never do over their common rows.
std::optional<double> separation_mm(const ShearResult& a, const ShearResult& b,
                                    double threshold = kSeparationThreshold);

struct Chaos {
  bool measured = false;               // the reference member and its twin both ran
  std::optional<double> separation;    // mm
  double largest_difference = 0;       // of tau/sigma over the test
  double peak_difference = 0, residual_difference = 0, dilatancy_difference = 0;  // deg
};
// The reference's seed-1 member of `specimen` against its twin `twin_knob`
// (kTwinKnob or kShearTwinKnob, study.h).
Chaos measure_chaos(const std::vector<StudyCase>& runs, StudySpecimen specimen,
                    const char* twin_knob = kTwinKnob);

// The columns both study CSVs (cases.csv, ensemble.csv) start with: a
// setting's knob, label and numerical choices; and the cells of one.
constexpr const char* kSettingsCsvHeader =
    "specimen,knob,label,dt_fraction,precision,stiffness_scale,inertial_number,skin_over_d,rolling,damping";
std::string settings_csv_cells(const StudySettings& s);
// A CSV cell in double quotes (its own double quotes become single ones).
std::string csv_quoted(std::string s);

// ensemble.csv: one row per setting, every interval as mean and half width,
// and back (the columns found by their names; throws std::runtime_error
// naming a missing column or a malformed row). What comes back is what the
// tables need: the settings, runs, intervals, errors, cost and failure.
std::string ensemble_csv(const std::vector<SettingSummary>& settings);
std::vector<SettingSummary> parse_ensemble_csv(const std::string& text);
// One specimen's settings' table of summary.md (and of docs/accuracy.md,
// generated from the shipped ensemble.csv by `simsols study table`); the
// "x ref" column is the cost against that specimen's reference.
std::string ensemble_table_md(const std::vector<SettingSummary>& settings, StudySpecimen specimen);

// The charts alone (study.cpp; error_vs_time_<knob>.png per knob, pareto.png; the
// poured specimen's with the prefix poured_), from the settings' summaries:
// a finished study's ensemble.csv draws them again.
void write_study_charts(const std::string& dir, const std::vector<SettingSummary>& settings);
// "the paper's layered specimen (...) in ...": what the study built.
std::string specimen_description(const StudyPreset& preset, StudySpecimen specimen);
// summary.md: per specimen, the settings' table (means, intervals, errors
// and their significance, cost), the chaos measured, the recommendation;
// then the contact checks.
std::string ensemble_summary_md(const StudyPreset& preset,
                                const std::vector<SettingSummary>& settings,
                                const std::vector<StudyCase>& runs);

}  // namespace simsols
