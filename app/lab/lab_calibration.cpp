#include "app/lab/lab_calibration.h"

namespace simsols {

std::string LabCalibration::load(const std::string& path, const std::string& target) {
  try {
    std::vector<std::pair<std::string, double>> values = read_calibrated(path);
    const std::vector<CalibrationTarget> targets = read_calibrated_measured(path);
    const CalibrationTarget* chosen = targets.empty() ? nullptr : &targets.front();
    std::string names;
    for (const CalibrationTarget& t : targets) {
      names += (names.empty() ? "" : ", ") + t.name;
      if (t.name == target) chosen = &t;
    }
    if (!target.empty() && (!chosen || chosen->name != target))
      return path + ": no measured curve '" + target + "'" +
             (names.empty() ? std::string(" (it has none)") : "; it has: " + names);
    Curve measured = chosen ? measured_curve(*chosen) : Curve{};
    values_ = std::move(values);
    target_ = chosen ? *chosen : CalibrationTarget{};
    measured_ = std::move(measured);
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

void LabCalibration::overlay(std::vector<LabPlot>& plots) const {
  for (LabPlot& p : plots) {
    if (p.x_quantity.empty() || p.x_quantity != target_.x.quantity) continue;
    for (size_t j = 0; j < target_.y.size(); ++j) {
      if (target_.y[j].quantity != p.y_quantity) continue;
      p.measured_x.clear();
      p.measured_y.clear();
      for (size_t i = 0; i < measured_.x.size(); ++i) {
        p.measured_x.push_back(measured_.x[i] * p.x_per_si);
        p.measured_y.push_back(measured_.y[j][i] * p.y_per_si);
      }
      p.measured_label = "measured: " + target_.name;
    }
  }
}

}  // namespace simsols
