// Live plots of the lab, drawn with Dear ImGui's draw lists: one curve,
// axes with 1-2-5 ticks (chart.h's nice_ticks, so they read like the PNG
// plots of the campaign), units in the axis titles, the peak marked.
#pragma once

#include <imgui.h>

#include <optional>
#include <string>
#include <vector>

namespace simsols {

struct LabPlot {
  std::string title, x_label, y_label;
  std::vector<double> x, y;
  std::optional<std::size_t> peak;  // index of the marked point
};

// Draws the plot in a child region of `size` (ImGui units).
void draw_lab_plot(const char* id, const LabPlot& plot, ImVec2 size);

}  // namespace simsols
