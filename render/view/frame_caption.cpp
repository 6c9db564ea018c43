#include "render/view/frame_caption.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/plot/font.h"

namespace simsols::render {
namespace {

constexpr plot::Color kInk{236, 238, 242}, kPanel{16, 18, 22};
constexpr double kPanelCover = 0.62;

// A translucent dark rectangle behind text, clipped to the image.
void shade(plot::Image& img, const plot::Rect& r) {
  for (int y = std::max(0, r.y0); y < std::min(img.height, r.y1); ++y)
    for (int x = std::max(0, r.x0); x < std::min(img.width, r.x1); ++x)
      plot::blend_pixel(img, x, y, kPanel, kPanelCover);
}

double unit(const plot::Image& img) { return std::max(0.5, img.height / 900.0); }

}  // namespace

plot::Rect draw_caption(plot::Image& img, const FrameCaption& c) {
  const double u = unit(img), title_px = 21 * u, state_px = 16 * u, pad = 10 * u, margin = 16 * u;
  double width = 0, height = pad;
  if (!c.title.empty()) {
    width = std::max(width, plot::text_width(c.title, title_px) + 0.15 * title_px);
    height += title_px * 1.25;
  }
  if (!c.state.empty()) {
    width = std::max(width, plot::text_width(c.state, state_px) + 0.15 * state_px);
    height += state_px * 1.3;
  }
  if (width == 0 || img.width < 120 || img.height < 120) return {0, 0, 0, 0};
  const plot::Rect r{int(margin), int(margin), int(std::ceil(margin + width + 2 * pad)),
                     int(std::ceil(margin + height + pad * 0.6))};
  shade(img, r);
  double y = margin + pad;
  if (!c.title.empty()) {
    y += title_px * 0.95;
    plot::draw_text(img, margin + pad, y, c.title, title_px, kInk, {}, false, 1.15);
    y += title_px * 0.3;
  }
  if (!c.state.empty()) plot::draw_text(img, margin + pad, y + state_px * 1.05, c.state, state_px, kInk);
  return r;
}

double scale_bar_length(double most) {
  const double p = std::pow(10.0, std::floor(std::log10(most)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= most * (1 + 1e-9)) return m * p;
  return p;
}

plot::Rect draw_scale_bar(plot::Image& img, const Camera& camera) {
  if (img.width < 120 || img.height < 120) return {0, 0, 0, 0};
  // pixels per metre at the target, along the screen's right
  const Camera::Projected a = camera.project(camera.target, img.width, img.height);
  const Camera::Projected b = camera.project(camera.target + 1e-3 * camera.right(), img.width, img.height);
  const double per_m = std::abs(b.pixel.x - a.pixel.x) / 1e-3;
  if (!(per_m > 0) || !std::isfinite(per_m)) return {0, 0, 0, 0};
  const double length = scale_bar_length(img.width / 6.0 / per_m), px = length * per_m;
  const double u = unit(img), text_px = 15 * u, pad = 9 * u, margin = 16 * u, thick = 3 * u;
  char label[64];
  std::snprintf(label, sizeof label, "%g mm at the centre", length * 1e3);
  const double w = std::max(px, plot::text_width(label, text_px)) + 2 * pad;
  const double h = pad + text_px * 1.2 + 4 * u + thick + 3 * u + pad;
  const plot::Rect r{int(margin), int(img.height - margin - h), int(std::ceil(margin + w)),
                     int(img.height - margin)};
  shade(img, r);
  const double x0 = margin + pad, y_text = r.y0 + pad + text_px * 0.95, y_bar = y_text + text_px * 0.3 + 4 * u;
  plot::draw_text(img, x0, y_text, label, text_px, kInk);
  plot::fill_rect(img, x0, y_bar, x0 + px, y_bar + thick, kInk);
  for (double x : {x0, x0 + px - thick})  // end ticks
    plot::fill_rect(img, x, y_bar - 4 * u, x + thick, y_bar + thick, kInk);
  return r;
}

}  // namespace simsols::render
