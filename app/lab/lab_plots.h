// Live plots of the lab, drawn with Dear ImGui's draw lists: one curve,
// axes with 1-2-5 ticks (chart.h's nice_ticks, so they read like the PNG
// plots of the campaign), units in the axis titles, the peak marked; x on
// a log axis when asked (e - log p', e - log sigma'v), decades labelled by
// value, points at x <= 0 left out (as chart.h's Chart::x_log).
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
  bool x_log = false;
};

// Draws the plot in a child region of width x height (ImGui units).
void draw_lab_plot(const char* id, const LabPlot& plot, float width, float height);

}  // namespace simsols
