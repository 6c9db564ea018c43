// A calibration's result in the lab (docs/calibration.md, docs/lab.md):
// its material applied to the scene of the next preparation, and the
// measured curve it was fitted to drawn over the live plots.
//
// load() reads a calibrated.toml (`simsols calibrate` writes it): the
// [calibrated] values, and the [[measured]] curves of the calibration's
// targets with their quantities. The lab sets the values that name a
// material's field on its scene (set_material_values, scene_keys.h);
// overlay() gives each live plot whose axes measure a target's x and y
// quantities (LabPlot::x_quantity, y_quantity) that target's points, in
// the plot's units. Other values (a preparation's key) are reported, not
// set: the lab's own controls make its specimen.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "app/experiment/calibration/calibration_spec.h"
#include "app/experiment/calibration/curves.h"
#include "app/lab/lab_plots.h"

namespace simsols {

class LabCalibration {
 public:
  // Reads `path`; the measured curves of the target called `target` ("" =
  // the first). Returns an error text, or "".
  std::string load(const std::string& path, const std::string& target);
  bool loaded() const { return !values_.empty(); }
  const std::vector<std::pair<std::string, double>>& values() const { return values_; }
  const std::string& target() const { return target_.name; }
  // Fills the measured points of every plot that measures the target's quantities.
  void overlay(std::vector<LabPlot>& plots) const;

 private:
  std::vector<std::pair<std::string, double>> values_;
  CalibrationTarget target_;
  Curve measured_;  // SI
};

}  // namespace simsols
