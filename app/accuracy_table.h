// The measured accuracy study (assets/accuracy/study.csv, written by
// `simsols study accuracy` and embedded at build time), for the lab's panel:
// next to the time-step and precision controls it shows the error on the
// peak friction angle and the cost that the study measured for the nearest
// case with those settings.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene.h"

namespace simsols {

struct AccuracyEntry {
  std::string label;
  double dt_fraction = 0;
  Precision precision = Precision::Float;
  double stiffness_scale = 1, inertial_number = 0;
  std::optional<double> peak_error_pct;  // vs the study's reference; none when it failed
  double wall_s = 0, reference_wall_s = 0;
  std::string status;  // "ok" or "failed: ..."
};

// The embedded study's cases (parsed once).
const std::vector<AccuracyEntry>& accuracy_table();
// The time-step / precision case nearest to these settings (stiffness 1).
const AccuracyEntry* expected_accuracy(double dt_fraction, Precision precision);

}  // namespace simsols
