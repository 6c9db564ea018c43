// Chart: 2D line charts as a paper's figures show them (shear stress against
// horizontal displacement, one curve per normal stress), rendered headless to
// an Image or a PNG file for `simsols campaign`.
//
// A chart is plain data: series (x, y vectors; NaN breaks a line), markers
// (a ring and a label, e.g. the peak), labels and optional axis limits.
// Limits left unset come from the data, widened to whole 1-2-5 tick steps;
// a flat range is padded. Series without a colour take the next colour of a
// colour-blind-friendly palette (Okabe & Ito). The legend goes into the
// corner of the plot area that hides the least data.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "render/plot/image.h"

namespace simsols::plot {

struct Series {
  std::string label;
  std::vector<double> x, y;
  std::optional<Color> color;
  bool line = true;
  bool markers = false;
  bool dashed = false;
  // Error bars: the half height of a vertical bar at each point (a 95 %
  // interval, say); empty for none, NaN or 0 for a point without one.
  std::vector<double> y_err = {};
};

struct Marker {
  double x, y;
  std::string label;
};

struct Chart {
  std::string title, x_label, y_label;
  std::vector<Series> series;
  std::vector<Marker> markers;
  std::optional<double> x_min, x_max, y_min, y_max;
  bool legend = true;
  // x on a log10 scale (an e-log sigma' curve): points with x <= 0 are left
  // out; ticks at 1, 2 and 5 x 10^k, labelled with their values.
  bool x_log = false;
};

// Where render_chart puts things: the plot area [left, right) x [top, bottom)
// in pixels and the data range it shows.
struct ChartLayout {
  int left = 0, top = 0, right = 0, bottom = 0;
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;
  std::vector<double> x_ticks, y_ticks;
  double x_step = 0.2, y_step = 0.2;  // tick spacing (of log10 x on a log axis)
  bool x_log = false;                 // x_lo, x_hi are then log10 of the range
  std::vector<std::string> x_labels;  // one per x tick
  // NaN for an x the axis cannot show (x <= 0 on a log axis).
  double px(double x) const {
    const double v = !x_log ? x : x > 0 ? std::log10(x) : NAN;
    return left + (v - x_lo) / (x_hi - x_lo) * (right - left);
  }
  double py(double y) const { return bottom - (y - y_lo) / (y_hi - y_lo) * (bottom - top); }
};

// The palette colour given to the i-th series that has none.
Color palette_color(std::size_t i);

// Ticks at multiples of a 1, 2 or 5 x 10^k step inside [lo, hi], about
// target_count of them; a single tick when lo == hi.
std::vector<double> nice_ticks(double lo, double hi, int target_count);

// Tick label texts for one axis: as many decimals as the step needs ("0.3",
// not "0.30000000004"), or m×10ⁿ for every label when the step is >= 10⁶ or
// all values are below 10⁻³ with a step below 10⁻⁴.
std::vector<std::string> tick_labels(const std::vector<double>& ticks, double step);
std::string format_tick(double value, double step);  // one label, same rules

ChartLayout chart_layout(const Chart& chart, int width = 1200, int height = 800);
Image render_chart(const Chart& chart, int width = 1200, int height = 800);
void write_chart_png(const Chart& chart, const std::string& path, int width = 1200,
                     int height = 800);

}  // namespace simsols::plot
