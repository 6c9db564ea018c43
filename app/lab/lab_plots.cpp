#include "app/lab/lab_plots.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "render/plot/chart.h"

namespace simsols {

namespace {

// What a plot shows: its points as plotted (x as log10 on a log axis, x <= 0
// left out there) with their indices into the plot's data, the axes' ranges
// (zero included on linear axes, the target, 8 % headroom, widened to the
// outer ticks) and the ticks.
struct Layout {
  std::vector<double> px, py, xt, yt, mx, my;  // m*: the measured points as plotted
  std::vector<std::size_t> index;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
};

Layout lay_out(const LabPlot& p) {
  Layout l;
  std::vector<double>& px = l.px;
  std::vector<double>& py = l.py;
  std::vector<std::size_t>& index = l.index;
  for (std::size_t i = 0; i < p.x.size() && i < p.y.size(); ++i) {
    if (p.x_log && !(p.x[i] > 0)) continue;
    px.push_back(p.x_log ? std::log10(p.x[i]) : p.x[i]);
    py.push_back(p.y[i]);
    index.push_back(i);
  }
  for (std::size_t i = 0; i < p.measured_x.size() && i < p.measured_y.size(); ++i) {
    if ((p.x_log && !(p.measured_x[i] > 0)) || !std::isfinite(p.measured_y[i])) continue;
    l.mx.push_back(p.x_log ? std::log10(p.measured_x[i]) : p.measured_x[i]);
    l.my.push_back(p.measured_y[i]);
  }
  double& x0 = l.x0;
  double& x1 = l.x1;
  double& y0 = l.y0;
  double& y1 = l.y1;
  std::vector<double> ax = px, ay = py;  // the range holds both curves
  ax.insert(ax.end(), l.mx.begin(), l.mx.end());
  ay.insert(ay.end(), l.my.begin(), l.my.end());
  if (!ax.empty()) {
    x0 = *std::min_element(ax.begin(), ax.end());
    x1 = *std::max_element(ax.begin(), ax.end());
    y0 = *std::min_element(ay.begin(), ay.end());
    y1 = *std::max_element(ay.begin(), ay.end());
    if (!p.x_log) {  // linear axes start at zero; a void ratio or log axis need not
      x0 = std::min(0.0, x0);
      y0 = std::min(0.0, y0);
      y1 = std::max(0.0, y1);
    }
  }
  if (p.target) {
    y0 = ax.empty() ? std::min(0.0, *p.target) : std::min(y0, *p.target);
    y1 = ax.empty() ? *p.target : std::max(y1, *p.target);
  }
  if (y1 > y0) y1 += 0.08 * (y1 - y0);  // headroom: the top of the curve and the peak marker
  if (p.x_log) x0 = std::floor(x0), x1 = std::max(x0 + 1, std::ceil(x1));  // whole decades
  if (x1 <= x0) x1 = x0 + 1;
  if (y1 <= y0) y1 = y0 + (y0 != 0 ? 0.01 * std::fabs(y0) : 1);
  l.xt = plot::nice_ticks(x0, x1, 5);
  if (p.x_log) {
    l.xt.clear();
    for (double d = x0; d <= x1 + 1e-9; d += 1) l.xt.push_back(d);
  }
  l.yt = plot::nice_ticks(y0, y1, 4);
  if (l.xt.size() >= 2) x0 = std::min(x0, l.xt.front()), x1 = std::max(x1, l.xt.back());
  if (l.yt.size() >= 2) y0 = std::min(y0, l.yt.front()), y1 = std::max(y1, l.yt.back());
  return l;
}

}  // namespace

void draw_lab_plot(const char* id, const LabPlot& p, float width, float height) {
  ImGui::BeginChild(id, {width, height}, true, ImGuiWindowFlags_NoScrollbar);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 o = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float fh = ImGui::GetFontSize();
  ImGui::TextUnformatted(p.title.c_str());
  if (p.peak && *p.peak < p.y.size()) {  // the peak's value on the title line, off the curve
    ImGui::SameLine();
    ImGui::TextColored({1.0f, 0.47f, 0.24f, 1.0f}, "peak %.3g", p.y[*p.peak]);
  }
  if (!p.measured_x.empty()) {  // whose the points are
    ImGui::SameLine();
    ImGui::TextColored({0.95f, 0.85f, 0.35f, 1.0f}, "• %s", p.measured_label.c_str());
  }
  // the y axis' name on the title line, right-aligned (off the curve)
  const ImU32 axis = IM_COL32(150, 155, 165, 255);
  const float yw = ImGui::CalcTextSize(p.y_label.c_str()).x;
  ImGui::GetWindowDrawList()->AddText({o.x + avail.x - yw - 0.4f * fh, o.y}, axis, p.y_label.c_str());
  // plot area: left margin for tick labels, bottom for ticks and x title
  const ImVec2 a(o.x + 4.2f * fh, o.y + 1.6f * fh);
  const ImVec2 b(o.x + avail.x - 0.6f * fh, o.y + avail.y - 2.3f * fh);
  if (b.x - a.x < 20 || b.y - a.y < 20) {
    ImGui::EndChild();
    return;
  }
  const ImU32 grid = IM_COL32(60, 64, 72, 255), line = IM_COL32(90, 170, 255, 255),
              peak = IM_COL32(255, 120, 60, 255), goal = IM_COL32(120, 210, 140, 255);
  const Layout l = lay_out(p);
  const std::vector<double>& px = l.px;
  const std::vector<double>& py = l.py;
  const std::vector<double>& xt = l.xt;
  const std::vector<double>& yt = l.yt;
  const std::vector<std::size_t>& index = l.index;
  const double x0 = l.x0, x1 = l.x1, y0 = l.y0, y1 = l.y1;
  auto X = [&](double v) { return float(a.x + (v - x0) / (x1 - x0) * (b.x - a.x)); };
  auto Y = [&](double v) { return float(b.y - (v - y0) / (y1 - y0) * (b.y - a.y)); };
  const double xs = xt.size() >= 2 ? xt[1] - xt[0] : 1, ys = yt.size() >= 2 ? yt[1] - yt[0] : 1;
  for (double v : xt) {
    dl->AddLine({X(v), a.y}, {X(v), b.y}, grid);
    // a log axis is labelled by value: 10, 100, 1000
    const double value = p.x_log ? std::pow(10.0, v) : v;
    const std::string s = plot::format_tick(value, p.x_log ? value : xs);
    // centred under its tick, but inside the child window (the last one
    // of a log axis, "1000", is wider than the margin right of the plot)
    const float w = ImGui::CalcTextSize(s.c_str()).x;
    const float left = std::clamp(X(v) - w / 2, o.x, o.x + avail.x - w);
    dl->AddText({left, b.y + 0.2f * fh}, axis, s.c_str());
  }
  for (double v : yt) {
    dl->AddLine({a.x, Y(v)}, {b.x, Y(v)}, grid);
    const std::string s = plot::format_tick(v, ys);
    dl->AddText({a.x - ImGui::CalcTextSize(s.c_str()).x - 0.3f * fh, Y(v) - 0.5f * fh}, axis,
                s.c_str());
  }
  dl->AddRect(a, b, axis);
  const ImVec2 xl = ImGui::CalcTextSize(p.x_label.c_str());
  dl->AddText({(a.x + b.x - xl.x) / 2, b.y + 1.2f * fh}, axis, p.x_label.c_str());
  std::vector<ImVec2> pts;
  pts.reserve(px.size());
  for (std::size_t i = 0; i < px.size(); ++i) pts.push_back({X(px[i]), Y(py[i])});
  dl->PushClipRect(a, b, true);
  if (p.target) {  // dashed, labelled at its right end
    const float ty = Y(*p.target);
    for (float x = a.x; x < b.x; x += 10) dl->AddLine({x, ty}, {std::min(x + 6, b.x), ty}, goal, 1.5f);
    const ImVec2 ts = ImGui::CalcTextSize("target");
    dl->AddText({b.x - ts.x - 4, ty + 2}, goal, "target");
  }
  const ImU32 measured = IM_COL32(242, 217, 89, 255);
  for (std::size_t i = 0; i < l.mx.size(); ++i)
    dl->AddCircleFilled({X(l.mx[i]), Y(l.my[i])}, 2.5f, measured, 8);
  if (pts.size() >= 2) dl->AddPolyline(pts.data(), int(pts.size()), line, 0, 2.0f);
  const auto marked = p.peak ? std::find(index.begin(), index.end(), *p.peak) : index.end();
  if (marked != index.end()) {
    const ImVec2 q = pts[std::size_t(marked - index.begin())];
    dl->AddCircle(q, 5, peak, 16, 2.0f);

  }
  dl->PopClipRect();
  ImGui::EndChild();
}

}  // namespace simsols
