#include "render/plot/chart.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "render/plot/font.h"
#include "render/plot/png.h"

namespace simsols::plot {
namespace {

constexpr Color kWhite{255, 255, 255}, kInk{20, 20, 20}, kGrid{222, 222, 222},
    kLegendBorder{160, 160, 160};

// Sizes in pixels, scaled with the image (1 at 1200 x 800).
struct Style {
  double u, tick_font, label_font, title_font, legend_font, line, frame, tick_len, pad;
};

Style style_for(int w, int h) {
  const double u = std::max(0.6, std::min(w / 1200.0, h / 800.0));
  const auto font = [u](double px) { return std::max(12.0, px * u); };  // legible when small
  return {
      u,     font(17), font(20), font(24), font(17), 2.6 * u, std::max(1.0, std::round(1.3 * u)),
      7 * u, 14 * u};
}

// A tick step m x 10^e (m = 1, 2 or 5). Multiples are computed as i * m / 10^-e
// so that they are the doubles nearest to the decimals (0.6, not 3 * 0.2).
struct Step {
  int m = 1, e = 0;
  double at(double i) const {
    return e >= 0 ? i * m * std::pow(10.0, e) : i * m / std::pow(10.0, -e);
  }
  double value() const { return at(1); }
};

// The smallest 1, 2 or 5 x 10^k at or above `raw` (> 0, finite).
Step nice_step(double raw) {
  int e = static_cast<int>(std::floor(std::log10(raw)));
  const double f = raw / std::pow(10.0, e);
  const int m = f <= 1 + 1e-9 ? 1 : f <= 2 + 1e-9 ? 2 : f <= 5 + 1e-9 ? 5 : (++e, 1);
  return {m, e};
}

std::vector<double> ticks_with_step(double lo, double hi, Step step) {
  std::vector<double> t;
  const double s = step.value();
  const double i0 = std::ceil(lo / s - 1e-9), i1 = std::floor(hi / s + 1e-9);
  if (!(i1 - i0 < 1000)) return t;
  for (double i = i0; i <= i1; ++i) t.push_back(i == 0 ? 0.0 : step.at(i));
  return t;
}

struct Axis {
  double lo, hi;
  Step step;
};

// Axis range from the data range [dlo, dhi] (empty when dlo > dhi) and the
// user's limits; free ends snap outwards to whole steps. With `headroom`, a
// free end that the data comes within 5 % of moves out one step (a peak is not
// drawn on the frame), unless the data end is 0 (an origin).
Axis axis_range(double dlo, double dhi, std::optional<double> omin, std::optional<double> omax,
                int target, bool headroom) {
  const bool have_data = dlo <= dhi;
  if (!have_data) dlo = 0, dhi = 1;
  const bool fix_lo = omin && std::isfinite(*omin), fix_hi = omax && std::isfinite(*omax);
  double lo = fix_lo ? *omin : dlo, hi = fix_hi ? *omax : dhi;
  if (hi < lo) {
    if (fix_lo && fix_hi)
      std::swap(lo, hi);
    else if (fix_hi)
      lo = hi - 1;
    else
      hi = lo + 1;
  }
  if (hi == lo) {
    const double pad = lo != 0 ? std::abs(lo) * 0.1 : 1.0;
    if (!fix_lo || fix_hi) lo -= pad;
    if (!fix_hi || fix_lo) hi += pad;
  }
  const double span = hi - lo;
  if (!std::isfinite(span) || !(span > 0)) return {0, 1, {2, -1}};
  const Step step = nice_step(span / target);
  if (!fix_lo) lo = step.at(std::floor(lo / step.value() + 1e-9));
  if (!fix_hi) hi = step.at(std::ceil(hi / step.value() - 1e-9));
  if (headroom && have_data) {
    const double near = 0.05 * (hi - lo);
    if (!fix_hi && std::abs(dhi) > 1e-9 * span && dhi > hi - near)
      hi = step.at(std::round(hi / step.value()) + 1);
    if (!fix_lo && std::abs(dlo) > 1e-9 * span && dlo < lo + near)
      lo = step.at(std::round(lo / step.value()) - 1);
  }
  if (!(hi > lo) || !std::isfinite(hi - lo)) return {0, 1, {2, -1}};  // denormal ranges
  return {lo, hi, step};
}

// The points of a series the axes can show as pixel polylines, broken at
// NaN/inf (and at x <= 0 on a log axis).
std::vector<std::vector<Point>> polylines(const Series& s, const ChartLayout& L) {
  std::vector<std::vector<Point>> out(1);
  const std::size_t n = std::min(s.x.size(), s.y.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Point p{L.px(s.x[i]), L.py(s.y[i])};
    if (std::isfinite(p.x) && std::isfinite(p.y)) {
      out.back().push_back(p);
    } else if (!out.back().empty()) {
      out.emplace_back();
    }
  }
  if (out.back().empty()) out.pop_back();
  return out;
}

std::vector<Color> series_colors(const Chart& c) {
  std::vector<Color> out;
  std::size_t next = 0;
  for (const Series& s : c.series) out.push_back(s.color ? *s.color : palette_color(next++));
  return out;
}

// Points every 3 pixels along the drawn curves, to keep labels off them.
std::vector<Point> curve_samples(const Chart& c, const ChartLayout& L) {
  std::vector<Point> out;
  for (const Series& s : c.series)
    for (const auto& line : polylines(s, L))
      for (std::size_t i = 0; i < line.size(); ++i) {
        const Point a = line[i], b = line[i + 1 < line.size() ? i + 1 : i];
        const int n = static_cast<int>(std::min(2000.0, 1 + std::hypot(b.x - a.x, b.y - a.y) / 3));
        for (int k = 0; k < n; ++k)
          out.push_back({a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n});
      }
  return out;
}

std::size_t count_inside(const std::vector<Point>& pts, double x0, double y0, double x1,
                         double y1) {
  return static_cast<std::size_t>(std::count_if(pts.begin(), pts.end(), [&](Point q) {
    return q.x >= x0 && q.x <= x1 && q.y >= y0 && q.y <= y1;
  }));
}

void draw_legend(Image& img, const Chart& c, const ChartLayout& L, const Style& st,
                 const std::vector<Color>& colors, const std::vector<Point>& samples) {
  std::vector<std::size_t> entries;
  double label_w = 0;
  for (std::size_t i = 0; i < c.series.size(); ++i)
    if (!c.series[i].label.empty()) {
      entries.push_back(i);
      label_w = std::max(label_w, text_width(c.series[i].label, st.legend_font));
    }
  if (!c.legend || entries.empty()) return;
  const double inner = 10 * st.u, swatch = 36 * st.u, gap = 10 * st.u, row = 1.5 * st.legend_font;
  const double bw = 2 * inner + swatch + gap + label_w,
               bh = 2 * inner + row * entries.size() - 0.3 * row;
  const double m = 12 * st.u;
  // Corners in order of preference; take the one that hides the fewest samples of the curves.
  const Point corners[] = {{L.right - m - bw, L.top + m},
                           {L.left + m, L.top + m},
                           {L.right - m - bw, L.bottom - m - bh},
                           {L.left + m, L.bottom - m - bh}};
  Point at = corners[0];
  std::size_t best = std::numeric_limits<std::size_t>::max();
  for (const Point& p : corners)
    if (const std::size_t n = count_inside(samples, p.x - 4, p.y - 4, p.x + bw + 4, p.y + bh + 4);
        n < best)
      best = n, at = p;
  at = {std::round(at.x) + 0.5, std::round(at.y) + 0.5};  // crisp 1-pixel border
  const Rect clip{L.left, L.top, L.right, L.bottom};
  fill_rect(img, at.x, at.y, at.x + bw, at.y + bh, {255, 255, 255, 235}, clip);
  stroke_polylines(img, {{at, {at.x + bw, at.y}, {at.x + bw, at.y + bh}, {at.x, at.y + bh}, at}},
                   1.0, kLegendBorder, clip);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const Series& s = c.series[entries[k]];
    const Color col = colors[entries[k]];
    const double y = at.y + inner + row * (k + 0.5) - 0.15 * row, x = at.x + inner;
    if (s.line || !s.markers)
      draw_line(img, {x, y}, {x + swatch, y}, st.line, col, clip,
                s.dashed ? Dash{9 * st.u, 5 * st.u} : Dash{});
    if (s.markers) fill_circle(img, x + swatch / 2, y, 4 * st.u, col, clip);
    draw_text(img, x + swatch + gap, y, s.label, st.legend_font, kInk,
              {HAlign::left, VAlign::middle});
  }
}

void draw_marker(Image& img, const Marker& mk, const ChartLayout& L, const Style& st,
                 const std::vector<Point>& samples) {
  const double x = L.px(mk.x), y = L.py(mk.y), r = 8 * st.u;
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  const Rect clip{L.left, L.top, L.right, L.bottom};
  stroke_circle(img, x, y, r, 2.2 * st.u, kInk, clip);
  if (mk.label.empty() || !(x >= L.left && x <= L.right && y >= L.top && y <= L.bottom)) return;
  const double fs = st.legend_font, tw = text_width(mk.label, fs), cap = text_cap_height(fs);
  const double h = 4 * st.u, dx = r + 4 * st.u, dy = r + 2 * st.u;
  // Upper right, upper left, lower right, lower left of the ring: the first
  // inside the plot area that covers the fewest curve samples.
  double tx = x + dx, ty = y - dy;
  std::size_t best = std::numeric_limits<std::size_t>::max();
  for (const auto& [sx, sy] : {std::pair{1, -1}, {-1, -1}, {1, 1}, {-1, 1}}) {
    const double cx = sx > 0 ? x + dx : x - dx - tw, cy = sy < 0 ? y - dy : y + dy + cap;
    if (cx - h < L.left || cx + tw + h > L.right || cy - cap - h < L.top ||
        cy + text_descent(fs) + h > L.bottom)
      continue;
    if (const std::size_t n = count_inside(samples, cx - h, cy - cap - h, cx + tw + h, cy + h);
        n < best)
      best = n, tx = cx, ty = cy;
  }
  fill_rect(img, tx - h, ty - cap - h, tx + tw + h, ty + text_descent(fs) + h / 2,
            {255, 255, 255, 200}, clip);
  draw_text(img, tx, ty, mk.label, fs, kInk);
}

}  // namespace

Color palette_color(std::size_t i) {
  // Okabe & Ito (2008), yellow last: it is faint on white.
  static constexpr Color kPalette[] = {{0, 114, 178},   {213, 94, 0},  {0, 158, 115},
                                       {204, 121, 167}, {230, 159, 0}, {86, 180, 233},
                                       {0, 0, 0},       {240, 228, 66}};
  return kPalette[i % std::size(kPalette)];
}

std::vector<double> nice_ticks(double lo, double hi, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) return {lo};
  const double raw = (hi - lo) / std::max(1, target_count);
  return std::isfinite(raw) ? ticks_with_step(lo, hi, nice_step(raw)) : std::vector<double>{};
}

std::vector<std::string> tick_labels(const std::vector<double>& ticks, double step) {
  step = std::abs(step);
  double mag = 0;
  for (double t : ticks) mag = std::max(mag, std::abs(t));
  if (!(step > 0) || !std::isfinite(step)) step = mag > 0 && std::isfinite(mag) ? mag : 1;
  // One notation per axis: m×10ⁿ for very large steps or very small values.
  const bool sci = step >= 1e6 || (step < 1e-4 && mag < 1e-3);
  const int step_exp = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  static constexpr const char* kSup[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::vector<std::string> out;
  for (double v : ticks) {
    if (std::abs(v) < step * 1e-9) v = 0;
    char buf[64];
    if (!sci) {
      const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed,
                                   std::clamp(-step_exp, 0, 12));
      out.emplace_back(buf, r.ptr);
      continue;
    }
    if (v == 0 || !std::isfinite(v)) {
      out.push_back(v == 0 ? "0" : "?");
      continue;
    }
    int e = static_cast<int>(std::floor(std::log10(std::abs(v)) + 1e-9));
    const int digits = std::clamp(e - step_exp, 0, 14);
    double m = v / std::pow(10.0, e);
    if (std::abs(m) >= 10 - 0.5 * std::pow(10.0, -digits)) m /= 10, ++e;  // 9.99.. rounds to 10
    const auto r = std::to_chars(buf, buf + sizeof buf, m, std::chars_format::fixed, digits);
    std::string text(buf, r.ptr);
    if (text.find('.') != std::string::npos) {
      while (text.back() == '0') text.pop_back();
      if (text.back() == '.') text.pop_back();
    }
    text += "×10";
    if (e < 0) text += "⁻";
    for (char d : std::to_string(std::abs(e))) text += kSup[d - '0'];
    out.push_back(std::move(text));
  }
  return out;
}

std::string format_tick(double v, double step) { return tick_labels({v}, step)[0]; }

namespace {

// Ticks of a log axis over [10^lo, 10^hi]: 1, 2 and 5 x 10^k.
std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  for (int k = static_cast<int>(std::floor(lo)) - 1; k <= static_cast<int>(std::ceil(hi)); ++k)
    for (double m : {1.0, 2.0, 5.0}) {
      const double t = m * std::pow(10.0, k), v = std::log10(t);
      if (v >= lo - 1e-9 && v <= hi + 1e-9) ticks.push_back(t);
    }
  return ticks;
}

// "25", "0.5", "2000": the value with no trailing zeros.
std::string format_log_tick(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", t);
  return buf;
}

}  // namespace

ChartLayout chart_layout(const Chart& c, int w, int h) {
  if (w < 100 || h < 80 || w > 16384 || h > 16384)
    throw std::invalid_argument("chart size must be within 100 x 80 .. 16384 x 16384 pixels");
  const Style st = style_for(w, h);
  constexpr double inf = std::numeric_limits<double>::infinity();
  double xlo = inf, xhi = -inf, ylo = inf, yhi = -inf;
  const auto add = [&](double x, double y) {
    if (c.x_log) x = x > 0 ? std::log10(x) : NAN;
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    xlo = std::min(xlo, x), xhi = std::max(xhi, x), ylo = std::min(ylo, y), yhi = std::max(yhi, y);
  };
  for (const Series& s : c.series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      add(s.x[i], s.y[i]);
      if (i < s.y_err.size() && std::isfinite(s.y_err[i])) {
        add(s.x[i], s.y[i] - s.y_err[i]);
        add(s.x[i], s.y[i] + s.y_err[i]);
      }
    }
  for (const Marker& m : c.markers) add(m.x, m.y);

  ChartLayout L;
  std::optional<double> x_min = c.x_min, x_max = c.x_max;
  if (c.x_log) {
    if (x_min) x_min = std::log10(*x_min);
    if (x_max) x_max = std::log10(*x_max);
  }
  const Axis ax = axis_range(xlo, xhi, x_min, x_max, std::clamp(w / 110, 4, 10), false);
  const Axis ay = axis_range(ylo, yhi, c.y_min, c.y_max, std::clamp(h / 90, 4, 9), true);
  L.x_lo = ax.lo, L.x_hi = ax.hi, L.y_lo = ay.lo, L.y_hi = ay.hi;
  L.x_ticks = ticks_with_step(ax.lo, ax.hi, ax.step);
  L.y_ticks = ticks_with_step(ay.lo, ay.hi, ay.step);
  L.x_step = ax.step.value(), L.y_step = ay.step.value();
  L.x_log = c.x_log;
  if (c.x_log) {
    L.x_ticks = log_ticks(ax.lo, ax.hi);
    for (double t : L.x_ticks) L.x_labels.push_back(format_log_tick(t));
  } else {
    L.x_labels = tick_labels(L.x_ticks, L.x_step);
  }

  double ytick_w = 0;
  for (const std::string& t : tick_labels(L.y_ticks, L.y_step))
    ytick_w = std::max(ytick_w, text_width(t, st.tick_font));
  const std::vector<std::string>& xl = L.x_labels;
  const double xlast_w = xl.empty() ? 0 : text_width(xl.back(), st.tick_font);
  const double label_h = text_cap_height(st.label_font) + text_descent(st.label_font);
  const double gap = 0.6 * st.pad;

  double left = st.pad + ytick_w + gap + st.tick_len;
  if (!c.y_label.empty()) left += label_h + st.pad;
  double top = st.pad + text_cap_height(st.tick_font);
  if (!c.title.empty())
    top += text_cap_height(st.title_font) + text_descent(st.title_font) + st.pad;
  double bottom = st.pad + st.tick_len + gap + text_cap_height(st.tick_font);
  if (!c.x_label.empty()) bottom += label_h + st.pad;
  const double right = std::max(2 * st.pad, xlast_w / 2 + st.pad);
  L.left = static_cast<int>(std::round(left));
  L.top = static_cast<int>(std::round(top));
  L.right = std::max(L.left + 10, w - static_cast<int>(std::round(right)));
  L.bottom = std::max(L.top + 10, h - static_cast<int>(std::round(bottom)));
  return L;
}

namespace {

// Vertical bars of +-y_err with short caps, in the series' colour.
void draw_error_bars(Image& img, const Series& s, const ChartLayout& L, const Style& st,
                     const Color& col, const Rect& clip) {
  const std::size_t n = std::min({s.x.size(), s.y.size(), s.y_err.size()});
  const double cap = 4 * st.u;
  for (std::size_t i = 0; i < n; ++i) {
    const double e = s.y_err[i];
    if (!std::isfinite(e) || e <= 0 || !std::isfinite(s.y[i])) continue;
    const double x = L.px(s.x[i]), y0 = L.py(s.y[i] - e), y1 = L.py(s.y[i] + e);
    if (!std::isfinite(x)) continue;
    draw_line(img, {x, y0}, {x, y1}, st.line, col, clip);
    draw_line(img, {x - cap, y0}, {x + cap, y0}, st.line, col, clip);
    draw_line(img, {x - cap, y1}, {x + cap, y1}, st.line, col, clip);
  }
}

}  // namespace

Image render_chart(const Chart& c, int w, int h) {
  const ChartLayout L = chart_layout(c, w, h);
  const Style st = style_for(w, h);
  Image img = make_image(w, h, kWhite);
  const Rect clip{L.left, L.top, L.right, L.bottom};

  // Grid, pixel-aligned.
  for (double t : L.x_ticks) {
    const double x = std::floor(L.px(t)) + 0.5;
    draw_line(img, {x, double(L.top)}, {x, double(L.bottom)}, 1.0, kGrid, clip);
  }
  for (double t : L.y_ticks) {
    const double y = std::floor(L.py(t)) + 0.5;
    draw_line(img, {double(L.left), y}, {double(L.right), y}, 1.0, kGrid, clip);
  }

  // Data.
  const std::vector<Color> colors = series_colors(c);
  for (std::size_t i = 0; i < c.series.size(); ++i) {
    const Series& s = c.series[i];
    const auto lines = polylines(s, L);
    if (s.line)
      stroke_polylines(img, lines, st.line, colors[i], clip,
                       s.dashed ? Dash{9 * st.u, 5 * st.u} : Dash{});
    if (s.markers)
      for (const auto& line : lines)
        for (const Point& p : line) fill_circle(img, p.x, p.y, 4 * st.u, colors[i], clip);
    draw_error_bars(img, s, L, st, colors[i], clip);
  }
  const std::vector<Point> samples = curve_samples(c, L);
  for (const Marker& m : c.markers) draw_marker(img, m, L, st, samples);

  // Frame, ticks (outwards) and tick labels.
  const double f = st.frame, l = L.left, r = L.right, t = L.top, b = L.bottom;
  fill_rect(img, l - f, t - f, r + f, t, kInk);
  fill_rect(img, l - f, b, r + f, b + f, kInk);
  fill_rect(img, l - f, t, l, b, kInk);
  fill_rect(img, r, t, r + f, b, kInk);
  const double gap = 0.6 * st.pad;
  const std::vector<std::string>& xl = L.x_labels;
  for (std::size_t i = 0; i < L.x_ticks.size(); ++i) {
    const double x = std::floor(L.px(L.x_ticks[i])) + 0.5;
    fill_rect(img, x - f / 2, b + f, x + f / 2, b + st.tick_len, kInk);
    draw_text(img, x, b + st.tick_len + gap, xl[i], st.tick_font, kInk,
              {HAlign::center, VAlign::top});
  }
  const std::vector<std::string> yl = tick_labels(L.y_ticks, L.y_step);
  for (std::size_t i = 0; i < L.y_ticks.size(); ++i) {
    const double y = std::floor(L.py(L.y_ticks[i])) + 0.5;
    fill_rect(img, l - st.tick_len, y - f / 2, l - f, y + f / 2, kInk);
    draw_text(img, l - st.tick_len - gap, y, yl[i], st.tick_font, kInk,
              {HAlign::right, VAlign::middle});
  }

  // Labels and title.
  if (!c.x_label.empty())
    draw_text(img, (l + r) / 2, h - st.pad, c.x_label, st.label_font, kInk,
              {HAlign::center, VAlign::bottom});
  if (!c.y_label.empty())
    draw_text(img, st.pad, (t + b) / 2, c.y_label, st.label_font, kInk,
              {HAlign::center, VAlign::top}, true);
  if (!c.title.empty())
    draw_text(img, (l + r) / 2, st.pad, c.title, st.title_font, kInk, {HAlign::center, VAlign::top},
              false, 1.25);

  draw_legend(img, c, L, st, colors, samples);
  return img;
}

void write_chart_png(const Chart& c, const std::string& path, int w, int h) {
  write_png(render_chart(c, w, h), path);
}

}  // namespace simsols::plot
