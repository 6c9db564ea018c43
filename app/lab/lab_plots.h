// Live plots of the lab, drawn with Dear ImGui's draw lists: one curve,
// axes with 1-2-5 ticks (chart.h's nice_ticks, so they read like the PNG
// plots of the campaign), the title and the y axis' name with its unit on
// the line above the plot area and the x axis' under it (never over the
// curve), the peak marked (its value on the title line), a target drawn
// as a dashed line (the normal stress the platen follows); 8 % headroom
// above the highest point, so the curve and the peak marker stay inside; x on a log axis when asked
// (e - log p', e - log sigma'v), decades labelled by value, points at
// x <= 0 left out (as chart.h's Chart::x_log). A measured curve, when
// given, is drawn as points over the simulated one and named on the title
// line.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace simsols {

struct LabPlot {
  LabPlot(std::string t, std::string x_axis, std::string y_axis)
      : title(std::move(t)), x_label(std::move(x_axis)), y_label(std::move(y_axis)) {}
  std::string title, x_label, y_label;
  std::vector<double> x, y;
  std::optional<std::size_t> peak;  // index of the marked point
  std::optional<double> target;     // a dashed horizontal line at this y, labelled "target"
  bool x_log = false;
  // The apparatus' quantities on its axes (registry.h CurveQuantity names;
  // "" for none) and the plot's units per SI unit (100 for a strain in %,
  // 1e-3 for kPa): what places a measured curve on it.
  std::string x_quantity, y_quantity;
  double x_per_si = 1, y_per_si = 1;
  void measures(std::string x_q, double x_scale, std::string y_q, double y_scale) {
    x_quantity = std::move(x_q), x_per_si = x_scale, y_quantity = std::move(y_q), y_per_si = y_scale;
  }
  // A measured curve drawn as points over the simulated one (the panel
  // fills them from a calibration's measured curves), in the plot's units.
  std::vector<double> measured_x, measured_y;
  std::string measured_label;
};

// Draws the plot in a child region of width x height (ImGui units).
void draw_lab_plot(const char* id, const LabPlot& plot, float width, float height);

}  // namespace simsols
