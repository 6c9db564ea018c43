// The measured accuracy study (assets/accuracy/ensemble.csv, written by
// `simsols study accuracy` and embedded at build time), for the lab's panel:
// next to the time-step and precision controls it shows the error on the
// peak friction angle, with its 95 % interval, and the cost that the study
// measured for the nearest setting.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/experiment/shear_box/study_ensemble.h"
#include "solver/scene/scene.h"

namespace simsols {

// The embedded study's settings (parsed once).
const std::vector<SettingSummary>& accuracy_table();
// The time-step / precision setting of `specimen` nearest to these
// (stiffness 1, inertial number of the baseline), or null.
const SettingSummary* expected_accuracy(double dt_fraction, Precision precision,
                                        StudySpecimen specimen);
// The study's specimen that `scene` is (the study measured shear tests:
// a layered or a poured shear-box specimen), or nothing for another kind.
std::optional<StudySpecimen> accuracy_study_specimen(const Scene& scene);
// The panel's line for it: "... against the most accurate settings:
// phi_peak +0.05 +- 0.08 deg, 0.07x their time (layered specimen, ...)";
// the poured specimen's adds phi_res.
std::string expected_accuracy_text(const SettingSummary& s);

// A run profile's measured effect (assets/accuracy/profiles.csv, embedded:
// the profile against `paper` on the same specimens, docs/accuracy.md "The
// fast profile"): the panel's line for `specimen`, or "" when the file has
// no row for them. Throws ReadError when the embedded file is malformed.
std::string profile_accuracy_text(const std::string& profile, StudySpecimen specimen);

}  // namespace simsols
