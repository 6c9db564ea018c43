#include "render/plot/image.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace simsols::plot {
namespace {

// floor/ceil to int, saturating far outside any image.
int ifloor(double v) { return static_cast<int>(std::floor(std::clamp(v, -1e8, 1e8))); }
int iceil(double v) { return static_cast<int>(std::ceil(std::clamp(v, -1e8, 1e8))); }

Rect effective_clip(const Image& img, const std::optional<Rect>& clip) {
  Rect r{0, 0, img.width, img.height};
  if (clip) {
    r.x0 = std::max(r.x0, clip->x0);
    r.y0 = std::max(r.y0, clip->y0);
    r.x1 = std::min(r.x1, clip->x1);
    r.y1 = std::min(r.y1, clip->y1);
  }
  return r;
}

// Distance from p to segment [a, b].
double segment_distance(Point p, Point a, Point b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// Coverage of a bounded region of the image, blended once at the end.
class CoverageMask {
 public:
  CoverageMask(const Image& img, const std::optional<Rect>& clip, double x0, double y0, double x1,
               double y1) {
    const Rect c = effective_clip(img, clip);
    r_.x0 = std::max(c.x0, ifloor(x0));
    r_.y0 = std::max(c.y0, ifloor(y0));
    r_.x1 = std::min(c.x1, iceil(x1) + 1);
    r_.y1 = std::min(c.y1, iceil(y1) + 1);
    if (r_.x1 > r_.x0 && r_.y1 > r_.y0)
      cov_.assign(static_cast<std::size_t>(r_.x1 - r_.x0) * (r_.y1 - r_.y0), 0.0f);
  }

  bool empty() const { return cov_.empty(); }

  void add(int x, int y, double c) {
    float& v = cov_[static_cast<std::size_t>(y - r_.y0) * (r_.x1 - r_.x0) + (x - r_.x0)];
    v = std::max(v, static_cast<float>(c));
  }

  // Capsule of half width hw around [a, b].
  void segment(Point a, Point b, double hw, double max_cov) {
    if (empty()) return;
    const double m = hw + 1.0;
    const double ymin = std::min(a.y, b.y), ymax = std::max(a.y, b.y);
    const int ry0 = std::max(r_.y0, ifloor(ymin - m));
    const int ry1 = std::min(r_.y1, iceil(ymax + m) + 1);
    for (int y = ry0; y < ry1; ++y) {
      const double yc = y + 0.5;
      // x range of the segment points whose y lies within the row band.
      double xa = a.x, xb = b.x;
      if (ymax > ymin) {
        const double ya = std::clamp(yc - m, ymin, ymax), yb = std::clamp(yc + m, ymin, ymax);
        xa = a.x + (b.x - a.x) * (ya - a.y) / (b.y - a.y);
        xb = a.x + (b.x - a.x) * (yb - a.y) / (b.y - a.y);
      }
      const int rx0 = std::max(r_.x0, ifloor(std::min(xa, xb) - m));
      const int rx1 = std::min(r_.x1, iceil(std::max(xa, xb) + m) + 1);
      for (int x = rx0; x < rx1; ++x) {
        const double d = segment_distance({x + 0.5, yc}, a, b);
        const double c = std::min(hw + 0.5 - d, max_cov);
        if (c > 0) add(x, y, c);
      }
    }
  }

  // Annulus between radii r_in (may be <= 0: a disc) and r_out.
  void ring(double cx, double cy, double r_in, double r_out) {
    for (int y = r_.y0; y < r_.y1; ++y)
      for (int x = r_.x0; x < r_.x1; ++x) {
        const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
        double c = std::clamp(r_out + 0.5 - d, 0.0, 1.0);
        if (r_in > 0) c = std::min(c, std::clamp(d - r_in + 0.5, 0.0, 1.0));
        if (c > 0) add(x, y, c);
      }
  }

  void blend(Image& img, Color col) const {
    const int w = r_.x1 - r_.x0;
    for (int y = r_.y0; y < r_.y1; ++y)
      for (int x = r_.x0; x < r_.x1; ++x) {
        const float c = cov_[static_cast<std::size_t>(y - r_.y0) * w + (x - r_.x0)];
        if (c > 0) blend_pixel(img, x, y, col, std::min(c, 1.0f));
      }
  }

 private:
  Rect r_{0, 0, 0, 0};
  std::vector<float> cov_;
};

// Splits polylines into the "on" pieces of a dash pattern; the phase runs on
// across the vertices of each polyline.
std::vector<std::vector<Point>> apply_dash(const std::vector<std::vector<Point>>& lines, Dash d) {
  std::vector<std::vector<Point>> out;
  for (const auto& line : lines) {
    if (line.size() < 2) continue;
    bool on = true;
    double left = d.on;  // length left in the current dash or gap
    std::vector<Point> piece{line[0]};
    for (std::size_t i = 1; i < line.size(); ++i) {
      Point a = line[i - 1];
      const Point b = line[i];
      double len = std::hypot(b.x - a.x, b.y - a.y);
      while (len > left) {
        const double t = left / len;
        const Point p{a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t};
        if (on) {
          piece.push_back(p);
          out.push_back(std::move(piece));
          piece.clear();
        } else {
          piece = {p};
        }
        on = !on;
        len -= left;
        a = p;
        left = on ? d.on : d.off;
      }
      left -= len;
      if (on) piece.push_back(b);
    }
    if (on && piece.size() >= 2) out.push_back(std::move(piece));
  }
  return out;
}

}  // namespace

Image make_image(int width, int height, Color background) {
  if (width <= 0 || height <= 0 || width > 32768 || height > 32768)
    throw std::invalid_argument("image size out of range");
  Image img{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
  fill(img, background);
  return img;
}

Color pixel(const Image& img, int x, int y) {
  const std::uint8_t* p = &img.rgba[(static_cast<std::size_t>(y) * img.width + x) * 4];
  return {p[0], p[1], p[2], p[3]};
}

void fill(Image& img, Color c) {
  for (std::size_t i = 0; i + 3 < img.rgba.size(); i += 4) {
    img.rgba[i] = c.r;
    img.rgba[i + 1] = c.g;
    img.rgba[i + 2] = c.b;
    img.rgba[i + 3] = c.a;
  }
}

void blend_pixel(Image& img, int x, int y, Color c, double coverage) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  const double a = std::clamp(coverage, 0.0, 1.0) * c.a / 255.0;
  if (a <= 0) return;
  std::uint8_t* p = &img.rgba[(static_cast<std::size_t>(y) * img.width + x) * 4];
  const auto mix = [a](std::uint8_t dst, std::uint8_t src) {
    return static_cast<std::uint8_t>(std::lround(dst + (src - dst) * a));
  };
  p[0] = mix(p[0], c.r);
  p[1] = mix(p[1], c.g);
  p[2] = mix(p[2], c.b);
  p[3] = static_cast<std::uint8_t>(std::lround(255.0 * a + p[3] * (1.0 - a)));
}

void fill_rect(Image& img, double x0, double y0, double x1, double y1, Color c,
               std::optional<Rect> clip) {
  if (!std::isfinite(x0 + y0 + x1 + y1)) return;
  if (x1 < x0) std::swap(x0, x1);
  if (y1 < y0) std::swap(y0, y1);
  const Rect r = effective_clip(img, clip);
  const int ix0 = std::max(r.x0, ifloor(x0));
  const int iy0 = std::max(r.y0, ifloor(y0));
  const int ix1 = std::min(r.x1, iceil(x1));
  const int iy1 = std::min(r.y1, iceil(y1));
  for (int y = iy0; y < iy1; ++y) {
    const double cy = std::min<double>(y + 1, y1) - std::max<double>(y, y0);
    for (int x = ix0; x < ix1; ++x) {
      const double cx = std::min<double>(x + 1, x1) - std::max<double>(x, x0);
      blend_pixel(img, x, y, c, cx * cy);
    }
  }
}

void fill_circle(Image& img, double cx, double cy, double r, Color c, std::optional<Rect> clip) {
  if (!std::isfinite(cx + cy + r)) return;
  CoverageMask m(img, clip, cx - r - 1, cy - r - 1, cx + r + 1, cy + r + 1);
  if (m.empty()) return;
  m.ring(cx, cy, 0.0, r);
  m.blend(img, c);
}

void stroke_circle(Image& img, double cx, double cy, double r, double thickness, Color c,
                   std::optional<Rect> clip) {
  if (!std::isfinite(cx + cy + r + thickness)) return;
  const double ro = r + thickness / 2;
  CoverageMask m(img, clip, cx - ro - 1, cy - ro - 1, cx + ro + 1, cy + ro + 1);
  if (m.empty()) return;
  m.ring(cx, cy, r - thickness / 2, ro);
  m.blend(img, c);
}

void draw_line(Image& img, Point a, Point b, double thickness, Color c, std::optional<Rect> clip,
               Dash dash) {
  stroke_polylines(img, {{a, b}}, thickness, c, clip, dash);
}

void stroke_polylines(Image& img, const std::vector<std::vector<Point>>& lines, double thickness,
                      Color c, std::optional<Rect> clip, Dash dash) {
  if (dash.on > 0 && dash.off > 0) {
    stroke_polylines(img, apply_dash(lines, dash), thickness, c, clip);
    return;
  }
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const auto& line : lines)
    for (const Point& p : line) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
  if (!(x1 >= x0) || !(thickness > 0)) return;
  const double hw = thickness / 2, m = hw + 1;
  CoverageMask mask(img, clip, x0 - m, y0 - m, x1 + m, y1 + m);
  if (mask.empty()) return;
  const double max_cov = std::min(1.0, thickness);  // hairlines fade instead of thinning
  const auto finite = [](Point p) { return std::isfinite(p.x) && std::isfinite(p.y); };
  for (const auto& line : lines) {
    if (line.size() == 1 && finite(line[0])) mask.segment(line[0], line[0], hw, max_cov);
    for (std::size_t i = 1; i < line.size(); ++i)
      if (finite(line[i - 1]) && finite(line[i])) mask.segment(line[i - 1], line[i], hw, max_cov);
  }
  mask.blend(img, c);
}

}  // namespace simsols::plot
