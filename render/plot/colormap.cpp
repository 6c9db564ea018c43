#include "render/plot/colormap.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "render/plot/chart.h"
#include "render/plot/font.h"

namespace simsols::plot {
namespace {

// ---- colour science (sRGB, D65) -------------------------------------------

struct Lab {
  double L, a, b;
};

constexpr double kWhiteX = 0.95047, kWhiteZ = 1.08883;  // D65, Y = 1

double srgb_encode(double c) {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

// Linear value of each 8-bit channel level.
const std::array<double, 256>& srgb_decode_table() {
  static const std::array<double, 256> table = [] {
    std::array<double, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[i] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    }
    return t;
  }();
  return table;
}

// L* of a relative luminance Y in [0, 1].
double lightness(double Y) {
  constexpr double d = 6.0 / 29;
  const double f = Y > d * d * d ? std::cbrt(Y) : Y / (3 * d * d) + 4.0 / 29;
  return 116 * f - 16;
}

double luminance(double r, double g, double b) {
  return 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
}

// Linear sRGB of a CIELAB colour, unclamped (outside [0, 1] = out of gamut).
std::array<double, 3> lab_to_linear(Lab c) {
  constexpr double d = 6.0 / 29;
  const auto finv = [](double f) { return f > d ? f * f * f : 3 * d * d * (f - 4.0 / 29); };
  const double fy = (c.L + 16) / 116;
  const double X = kWhiteX * finv(fy + c.a / 500), Y = finv(fy), Z = kWhiteZ * finv(fy - c.b / 200);
  return {3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z,
          -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
          0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z};
}

bool in_gamut(const std::array<double, 3>& rgb) {
  return std::all_of(rgb.begin(), rgb.end(), [](double v) { return v >= -1e-9 && v <= 1 + 1e-9; });
}

// Into sRGB by shrinking the chroma at constant L* (keeps the lightness
// ramp); the designed control points never need it by more than rounding.
std::array<double, 3> to_gamut(Lab c) {
  std::array<double, 3> rgb = lab_to_linear(c);
  if (!in_gamut(rgb)) {
    double lo = 0, hi = 1;
    for (int i = 0; i < 40; ++i) {
      const double m = (lo + hi) / 2;
      (in_gamut(lab_to_linear({c.L, c.a * m, c.b * m})) ? lo : hi) = m;
    }
    rgb = lab_to_linear({c.L, c.a * lo, c.b * lo});
  }
  for (double& v : rgb) v = std::clamp(v, 0.0, 1.0);
  return rgb;
}

// 8-bit colour nearest in lightness to `target_L` among the floor/ceil
// combinations of the channels: plain rounding can move L* by up to ~0.3,
// as much as one step of a 256-entry table, and would break monotonicity.
Color quantise(const std::array<double, 3>& rgb, double target_L) {
  const auto& dec = srgb_decode_table();
  int lo[3];
  double frac[3];
  for (int k = 0; k < 3; ++k) {
    const double v = std::clamp(255 * srgb_encode(rgb[k]), 0.0, 255.0);
    lo[k] = std::min(254, static_cast<int>(std::floor(v)));
    frac[k] = v - lo[k];
  }
  int best[3] = {lo[0], lo[1], lo[2]};
  double best_err = 1e300;
  for (int m = 0; m < 8; ++m) {
    int q[3];
    double off = 0;  // channel rounding distance: breaks ties towards plain rounding
    for (int k = 0; k < 3; ++k) {
      const int up = (m >> k) & 1;
      q[k] = lo[k] + up;
      off += up ? 1 - frac[k] : frac[k];
    }
    const double err =
        std::abs(lightness(luminance(dec[q[0]], dec[q[1]], dec[q[2]])) - target_L) + 1e-3 * off;
    if (err < best_err) best_err = err, std::copy(q, q + 3, best);
  }
  return {static_cast<std::uint8_t>(best[0]), static_cast<std::uint8_t>(best[1]),
          static_cast<std::uint8_t>(best[2])};
}

// ---- the maps -------------------------------------------------------------

// CIELAB of a linear sRGB colour.
Lab linear_to_lab(double r, double g, double b) {
  const double X = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / kWhiteX;
  const double Y = luminance(r, g, b);
  const double Z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / kWhiteZ;
  constexpr double d = 6.0 / 29;
  const auto f = [](double v) { return v > d * d * d ? std::cbrt(v) : v / (3 * d * d) + 4.0 / 29; };
  return {116 * f(Y) - 16, 500 * (f(X) - f(Y)), 200 * (f(Y) - f(Z))};
}

// CIELAB of an sRGB colour with channels in [0, 1].
Lab srgb_to_lab(const std::array<double, 3>& c) {
  const auto dec = [](double v) {
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  return linear_to_lab(dec(c[0]), dec(c[1]), dec(c[2]));
}

// Control points at t = i / (n - 1). L* is linear from the first to the last;
// a* and b* pass through every point on a uniform Catmull-Rom spline.
template <std::size_t N>
Lab ramp(const std::array<Lab, N>& p, double t) {
  constexpr int n = static_cast<int>(N);
  const double x = t * (n - 1);
  const int i = std::clamp(static_cast<int>(std::floor(x)), 0, n - 2);
  const double s = x - i, s2 = s * s, s3 = s2 * s;
  const auto P = [&](int k) { return p[std::clamp(k, 0, n - 1)]; };
  const auto cr = [&](double p0, double p1, double p2, double p3) {
    return 0.5 * (2 * p1 + (p2 - p0) * s + (2 * p0 - 5 * p1 + 4 * p2 - p3) * s2 +
                  (3 * p1 - p0 - 3 * p2 + p3) * s3);
  };
  const Lab a = P(i - 1), b = P(i), c = P(i + 1), d = P(i + 2);
  return {p.front().L + (p.back().L - p.front().L) * t, cr(a.a, b.a, c.a, d.a),
          cr(a.b, b.b, c.b, d.b)};
}

// A uniform Catmull-Rom spline through all three coordinates of points at
// t = i / (n - 1); beyond the ends the line through the last two points
// continues, so the end segments keep their slope.
template <std::size_t N>
Lab spline(const std::array<Lab, N>& p, double t) {
  constexpr int n = static_cast<int>(N);
  const double x = t * (n - 1);
  const int i = std::clamp(static_cast<int>(std::floor(x)), 0, n - 2);
  const double s = x - i, s2 = s * s, s3 = s2 * s;
  const auto P = [&](int k) -> Lab {
    if (k < 0) return {2 * p[0].L - p[1].L, 2 * p[0].a - p[1].a, 2 * p[0].b - p[1].b};
    if (k > n - 1)
      return {2 * p[n - 1].L - p[n - 2].L, 2 * p[n - 1].a - p[n - 2].a, 2 * p[n - 1].b - p[n - 2].b};
    return p[k];
  };
  const auto cr = [&](double p0, double p1, double p2, double p3) {
    return 0.5 * (2 * p1 + (p2 - p0) * s + (2 * p0 - 5 * p1 + 4 * p2 - p3) * s2 +
                  (3 * p1 - p0 - 3 * p2 + p3) * s3);
  };
  const Lab a = P(i - 1), b = P(i), c = P(i + 1), d = P(i + 2);
  return {cr(a.L, b.L, c.L, d.L), cr(a.a, b.a, c.a, d.a), cr(a.b, b.b, c.b, d.b)};
}

// Sequential: viridis (colormap.h), its published 256-entry table read at
// every 15th entry (t = k / 17), sRGB channels in [0, 1].
constexpr double kViridis[18][3] = {
    {0.267004, 0.004874, 0.329415}, {0.281924, 0.089666, 0.412415},
    {0.280255, 0.165693, 0.476498}, {0.263663, 0.237631, 0.518762},
    {0.237441, 0.305202, 0.541921}, {0.208623, 0.367752, 0.552675},
    {0.182256, 0.426184, 0.557120}, {0.159194, 0.482237, 0.558073},
    {0.137770, 0.537492, 0.554906}, {0.121148, 0.592739, 0.544641},
    {0.128087, 0.647749, 0.523491}, {0.180653, 0.701402, 0.488189},
    {0.274149, 0.751988, 0.436601}, {0.395174, 0.797475, 0.367757},
    {0.535621, 0.835785, 0.281908}, {0.688944, 0.865448, 0.182725},
    {0.845561, 0.887322, 0.099702}, {0.993248, 0.906157, 0.143936}};

Lab viridis(double t) {
  static const std::array<Lab, 18> points = [] {
    std::array<Lab, 18> p{};
    for (std::size_t k = 0; k < p.size(); ++k)
      p[k] = srgb_to_lab({kViridis[k][0], kViridis[k][1], kViridis[k][2]});
    return p;
  }();
  return spline(points, t);
}

// Diverging: Moreland's cool-warm (colormap.h), in his Msh coordinates:
// M = |(L*, a*, b*)|, s = acos(L* / M) (0 for a grey), h = atan2(b*, a*).
struct Msh {
  double M, s, h;
};

Msh to_msh(Lab c) {
  const double M = std::sqrt(c.L * c.L + c.a * c.a + c.b * c.b);
  return {M, M > 0 ? std::acos(std::clamp(c.L / M, -1.0, 1.0)) : 0.0, std::atan2(c.b, c.a)};
}

Lab from_msh(Msh c) {
  return {c.M * std::cos(c.s), c.M * std::sin(c.s) * std::cos(c.h),
          c.M * std::sin(c.s) * std::sin(c.h)};
}

// The paper's "adjust hue": the hue a grey of magnitude M_grey takes on the
// way to the saturated colour `sat`, turned away from it so that the hue
// change stays even in perceptual distance.
double adjust_hue(Msh sat, double M_grey) {
  if (sat.M >= M_grey) return sat.h;
  const double spin = sat.s * std::sqrt(M_grey * M_grey - sat.M * sat.M) / (sat.M * std::sin(sat.s));
  return sat.h > -std::numbers::pi / 3 ? sat.h + spin : sat.h - spin;
}

// Linear in Msh from the cool end to a grey of M = max(88, the ends' M) at
// t = 1/2 and on to the warm end; the grey's hue is adjusted towards the
// end of each half.
Lab cool_warm(double t) {
  static const Msh cool = to_msh(srgb_to_lab({59 / 255.0, 76 / 255.0, 192 / 255.0}));
  static const Msh warm = to_msh(srgb_to_lab({180 / 255.0, 4 / 255.0, 38 / 255.0}));
  const Msh end = t < 0.5 ? cool : warm;
  const double grey_M = std::max({cool.M, warm.M, 88.0}), grey_h = adjust_hue(end, grey_M);
  const double u = std::abs(2 * t - 1);  // 0 at the centre, 1 at the end
  return from_msh({grey_M + (end.M - grey_M) * u, end.s * u, grey_h + (end.h - grey_h) * u});
}

// Force: near-neutral warm light grey, orange, red, dark red.
constexpr std::array<Lab, 4> kForce{
    {{86, 4, 14}, {66.3, 24, 50}, {46.7, 50, 44}, {27, 46, 32}}};

// Categorical, as (L*, C*, hue in degrees): blue, orange, green, pink,
// yellow, sky, red, purple. Consecutive categories differ in hue by ~90° or
// more; the closest pair anywhere (orange/red, blue/purple) is ~38 apart.
constexpr double kCategoricalLCh[8][3] = {{52, 52, 280}, {68, 70, 60},  {60, 60, 140},
                                          {58, 68, 352}, {86, 75, 95},  {74, 32, 225},
                                          {44, 66, 35},  {36, 56, 318}};

const std::array<Color, 8>& categorical_colors() {
  static const std::array<Color, 8> colors = [] {
    std::array<Color, 8> out{};
    for (int k = 0; k < 8; ++k) {
      const double L = kCategoricalLCh[k][0], C = kCategoricalLCh[k][1],
                   h = kCategoricalLCh[k][2] * std::numbers::pi / 180;
      const std::array<double, 3> rgb = to_gamut({L, C * std::cos(h), C * std::sin(h)});
      const auto q = [](double v) {
        return static_cast<std::uint8_t>(std::lround(255 * srgb_encode(v)));
      };
      out[k] = {q(rgb[0]), q(rgb[1]), q(rgb[2])};
    }
    return out;
  }();
  return colors;
}

Color from_lab(Lab c) { return quantise(to_gamut(c), c.L); }

// Qualitative: Kelly's colours of maximum contrast (colormap.h), split into
// two halves of 10, each as varied as the split allows (smallest CIELAB
// distance within a half ~34, over all 20 ~15): even entries white, yellow,
// orange, red, buff, yellowish pink, violet, purplish red, yellow green,
// yellowish brown; odd entries purple, light blue, grey, green, purplish
// pink, blue, orange yellow, greenish yellow, reddish brown, reddish orange.
// Even identities take the even entries, odd ones the odd entries.
constexpr int kQualitative = 20;
constexpr std::uint32_t kQualitativeRgb[kQualitative] = {
    0xF2F3F4, 0x875692, 0xF3C300, 0xA1CAF1, 0xF38400, 0x848482, 0xBE0032,
    0x008856, 0xC2B280, 0xE68FAC, 0xF99379, 0x0067A5, 0x604E97, 0xF6A600,
    0xB3446C, 0xDCD300, 0x8DB600, 0x882D17, 0x654522, 0xE25822};

Color qualitative_color(int entry) {
  const std::uint32_t c = kQualitativeRgb[entry];
  return {static_cast<std::uint8_t>(c >> 16), static_cast<std::uint8_t>((c >> 8) & 0xFF),
          static_cast<std::uint8_t>(c & 0xFF)};
}

// ---- the legend -----------------------------------------------------------

struct Theme {
  Color panel, border, ink, frame;
};

Theme theme(bool dark) {
  if (dark) return {{24, 24, 28, 205}, {110, 110, 116}, {236, 236, 236}, {170, 170, 170}};
  return {{255, 255, 255, 218}, {150, 150, 150}, {24, 24, 24}, {80, 80, 80}};
}

// The texts, which do not depend on the size.
struct Texts {
  std::vector<double> tick_t;  // continuous: where each tick sits on the bar
  std::vector<std::string> tick_labels;
  std::vector<std::string> categories;  // Categorical
};

constexpr int kMaxSwatches = 16;

std::string ratio_label(double v) {
  if (!std::isfinite(v)) return "?";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 3);
  return {buf, r.ptr};
}

Texts legend_texts(const Legend& lg) {
  Texts t;
  if (lg.map == ColorMap::Qualitative) {
    // identities: no values to show
  } else if (lg.map == ColorMap::Categorical) {
    const double lo = std::isfinite(lg.min) ? std::round(lg.min) : 0;
    const double hi = std::isfinite(lg.max) ? std::round(lg.max) : lo;
    const int n = static_cast<int>(std::clamp(hi - lo + 1, 1.0, double{kMaxSwatches}));
    for (int k = 0; k < n; ++k)
      t.categories.push_back(static_cast<std::size_t>(k) < lg.category_labels.size()
                                 ? lg.category_labels[k]
                                 : ratio_label(lo + k));
  } else if (std::isfinite(lg.min) && std::isfinite(lg.max)) {
    std::vector<double> ticks;
    double step = 0;
    if (lg.min == lg.max) {
      ticks = {lg.min};
      t.tick_t = {0.5};
      step = lg.min != 0 ? std::abs(lg.min) : 1;
    } else {
      ticks = nice_ticks(lg.min, lg.max, 5);
      step = ticks.size() >= 2 ? ticks[1] - ticks[0] : std::abs(lg.max - lg.min);
      for (double v : ticks) t.tick_t.push_back(std::clamp((v - lg.min) / (lg.max - lg.min), 0.0, 1.0));
    }
    t.tick_labels = tick_labels(ticks, step);
  }
  return t;
}

// The note's lines (split at '\n'); none for an empty note.
std::vector<std::string> note_lines(const std::string& note) {
  std::vector<std::string> lines;
  std::size_t at = 0;
  while (at < note.size()) {
    const std::size_t end = std::min(note.find('\n', at), note.size());
    lines.push_back(note.substr(at, end - at));
    at = end + 1;
  }
  return lines;
}

// The legend laid out at `u` pixels per unit, relative to the panel's
// top-left corner.
struct Placed {
  double u = 1, font = 16, title_font = 18, line = 1, radius = 8, tick_len = 6;
  int w = 0, h = 0, margin = 0;
  Rect bar{0, 0, 0, 0};
  std::vector<Rect> swatches;
  double title_y = 0, label_x = 0;
  std::vector<double> note_y;  // one baseline per line of the note
  std::vector<double> tick_y;
};

// The colour scale (bar, swatches or strip) from height y of the panel,
// widening `right` to hold it; returns the height under it.
double place_scale(const Legend& lg, const Texts& tx, Placed& p, double y, double& right) {
  const double u = p.u, pad = 12 * u, gap = 8 * u, slack = 1 + 0.2 * p.font;
  const int x0 = static_cast<int>(std::round(pad)) + 1;  // + the bar's frame
  if (lg.map == ColorMap::Qualitative) {
    // a strip of the map's colours, as long as a continuous bar
    const int n = kQualitative;
    const int cw = std::max(2, static_cast<int>(std::round(12 * u)));
    const int ch = std::max(3, static_cast<int>(std::round(18 * u)));
    const int y0 = static_cast<int>(std::round(y)) + 1;
    for (int k = 0; k < n; ++k) p.swatches.push_back({x0 + k * cw, y0, x0 + (k + 1) * cw, y0 + ch});
    p.bar = {x0, y0, x0 + n * cw, y0 + ch};
    right = std::max(right, p.bar.x1 + 1.0);
    return p.bar.y1 + 1;
  }
  if (lg.map == ColorMap::Categorical) {
    const int sw = std::max(3, static_cast<int>(std::round(18 * u)));
    const int sg = std::max(2, static_cast<int>(std::round(6 * u)));
    const int y0 = static_cast<int>(std::round(y)) + 1;
    for (std::size_t k = 0; k < tx.categories.size(); ++k) {
      const int top = y0 + static_cast<int>(k) * (sw + sg);
      p.swatches.push_back({x0, top, x0 + sw, top + sw});
    }
    p.bar = {x0, y0, x0 + sw, p.swatches.back().y1};
    p.label_x = p.bar.x1 + 1 + gap;
    for (const std::string& s : tx.categories)
      right = std::max(right, p.label_x + text_width(s, p.font) + slack);
    return p.bar.y1 + 1;
  }
  // Tick labels are centred on their ticks: room for half a cap above and below.
  const double over = text_cap_height(p.font) / 2 + 1;
  const int y0 = static_cast<int>(std::round(y + over));
  const int len = std::max(8, static_cast<int>(std::round(240 * u)));
  p.bar = {x0, y0, x0 + std::max(4, static_cast<int>(std::round(22 * u))), y0 + len};
  for (double t : tx.tick_t) p.tick_y.push_back(p.bar.y1 - 0.5 - t * (len - 1));
  p.label_x = p.bar.x1 + 1 + p.tick_len + 0.5 * gap;
  right = std::max(right, p.bar.x1 + 1.0);
  for (const std::string& s : tx.tick_labels)
    right = std::max(right, p.label_x + text_width(s, p.font) + slack);
  return p.bar.y1 + 1 + over;
}

Placed place(const Legend& lg, const Texts& tx, double u) {
  Placed p;
  p.u = u;
  p.font = 17 * u;
  p.title_font = 19 * u;
  p.line = std::max(1.0, 1.3 * u);
  p.radius = 8 * u;
  p.tick_len = 6 * u;
  p.margin = static_cast<int>(std::max(2.0, std::round(16 * u)));
  const double pad = 12 * u, gap = 8 * u, slack = 1 + 0.2 * p.font;  // stroke ends past text_width
  double right = 0, y = pad;
  if (!lg.title.empty()) {
    p.title_y = y + text_cap_height(p.title_font);
    y = p.title_y + text_descent(p.title_font) + gap;
    right = pad + text_width(lg.title, p.title_font) + slack;
  }
  y = place_scale(lg, tx, p, y, right);
  const std::vector<std::string> lines = note_lines(lg.note);
  for (std::size_t k = 0; k < lines.size(); ++k) {
    p.note_y.push_back(y + (k == 0 ? gap : 0.3 * gap) + text_cap_height(p.font));
    y = p.note_y.back() + text_descent(p.font);
    right = std::max(right, pad + text_width(lines[k], p.font) + slack);
  }
  p.w = static_cast<int>(std::ceil(right + pad));
  p.h = static_cast<int>(std::ceil(y + pad));
  return p;
}

// Rounded-box signed distance (negative inside) at a pixel centre.
double rounded_box_distance(double px, double py, double w, double h, double r) {
  r = std::min({r, w / 2, h / 2});
  const double qx = std::abs(px - w / 2) - (w / 2 - r), qy = std::abs(py - h / 2) - (h / 2 - r);
  return std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0) - r;
}

void set_pixel(Image& img, int x, int y, Color c) { blend_pixel(img, x, y, c, 1.0); }

// A 1-pixel frame just outside r, so the colours inside stay exact.
void frame_outside(Image& img, Rect r, Color c) {
  for (int x = r.x0 - 1; x <= r.x1; ++x) set_pixel(img, x, r.y0 - 1, c), set_pixel(img, x, r.y1, c);
  for (int y = r.y0; y < r.y1; ++y) set_pixel(img, r.x0 - 1, y, c), set_pixel(img, r.x1, y, c);
}

// The colour scale: the strip, the swatches with their labels, or the bar
// with its ticks.
void render_scale(Image& img, const Legend& lg, const Texts& tx, const Placed& p, const Theme& th) {
  if (lg.map == ColorMap::Qualitative) {
    for (std::size_t k = 0; k < p.swatches.size(); ++k) {
      const Rect& s = p.swatches[k];
      const Color c = qualitative_color(static_cast<int>(k));
      for (int y = s.y0; y < s.y1; ++y)
        for (int x = s.x0; x < s.x1; ++x) set_pixel(img, x, y, c);
    }
    frame_outside(img, p.bar, th.frame);
  } else if (lg.map == ColorMap::Categorical) {
    for (std::size_t k = 0; k < p.swatches.size(); ++k) {
      const Rect& s = p.swatches[k];
      const Color c = colormap_color(ColorMap::Categorical, std::round(lg.min) + k);
      for (int y = s.y0; y < s.y1; ++y)
        for (int x = s.x0; x < s.x1; ++x) set_pixel(img, x, y, c);
      frame_outside(img, s, th.frame);
      draw_text(img, p.label_x, (s.y0 + s.y1) / 2.0, tx.categories[k], p.font, th.ink,
                {HAlign::left, VAlign::middle});
    }
  } else {
    const Rect& b = p.bar;
    const int len = b.y1 - b.y0;
    for (int y = b.y0; y < b.y1; ++y) {
      const Color c = colormap_color(lg.map, double(b.y1 - 1 - y) / (len - 1));
      for (int x = b.x0; x < b.x1; ++x) set_pixel(img, x, y, c);
    }
    frame_outside(img, b, th.frame);
    const double tx0 = b.x1 + 1 + p.line / 2;
    for (std::size_t k = 0; k < p.tick_y.size(); ++k) {
      draw_line(img, {tx0, p.tick_y[k]}, {tx0 + p.tick_len - p.line / 2, p.tick_y[k]}, p.line,
                th.ink);
      draw_text(img, p.label_x, p.tick_y[k], tx.tick_labels[k], p.font, th.ink,
                {HAlign::left, VAlign::middle});
    }
  }
}

// Draws the legend laid out as `p` into `img`, whose top-left pixel is the
// panel's (the image may be cut short at the right and bottom).
void render(Image& img, const Legend& lg, const Texts& tx, const Placed& p) {
  const Theme th = theme(lg.dark);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double d = rounded_box_distance(x + 0.5, y + 0.5, p.w, p.h, p.radius);
      blend_pixel(img, x, y, th.panel, 0.5 - d);
      blend_pixel(img, x, y, th.border, 1 - std::abs(d + 0.5));  // 1 px on the inner edge
    }
  if (!lg.title.empty())
    draw_text(img, p.bar.x0 - 1, p.title_y, lg.title, p.title_font, th.ink, {}, false, 1.1);

  render_scale(img, lg, tx, p, th);
  const std::vector<std::string> lines = note_lines(lg.note);
  for (std::size_t k = 0; k < lines.size(); ++k)
    draw_text(img, p.bar.x0 - 1, p.note_y[k], lines[k], p.font, th.ink);
}

struct Fitted {
  LegendLayout layout;
  Placed placed;
  Texts texts;
};

std::optional<Fitted> fit_legend(int W, int H, const Legend& lg) {
  if (W < 120 || H < 120) return std::nullopt;
  Fitted f;
  f.texts = legend_texts(lg);
  const double scale = lg.scale > 0 && std::isfinite(lg.scale) ? std::min(lg.scale, 20.0) : 1.0;
  // Below ~550 px the fonts would get too small to read; the fit below still
  // shrinks a legend that does not fit.
  double u = scale * std::max(0.55, H / 1000.0);
  for (int iter = 0;; ++iter) {
    f.placed = place(lg, f.texts, u);
    const double aw = W - 2.0 * f.placed.margin, ah = H - 2.0 * f.placed.margin;
    if ((f.placed.w <= aw && f.placed.h <= ah) || iter == 4) break;
    // Everything scales with u: one step nearly fits.
    u *= 0.98 * std::min(aw / f.placed.w, ah / f.placed.h);
  }
  const Placed& p = f.placed;
  const bool left = lg.corner == Legend::Corner::TopLeft || lg.corner == Legend::Corner::BottomLeft;
  const bool top = lg.corner == Legend::Corner::TopLeft || lg.corner == Legend::Corner::TopRight;
  const int x0 = std::max(0, left ? p.margin : W - p.margin - p.w);
  const int y0 = std::max(0, top ? p.margin : H - p.margin - p.h);
  const auto shift = [&](Rect r) { return Rect{r.x0 + x0, r.y0 + y0, r.x1 + x0, r.y1 + y0}; };
  f.layout.panel = {x0, y0, std::min(W, x0 + p.w), std::min(H, y0 + p.h)};
  f.layout.bar = shift(p.bar);
  for (const Rect& s : p.swatches) f.layout.swatches.push_back(shift(s));
  f.layout.unit = p.u;
  return f;
}

}  // namespace

// An integer hash with good avalanche: "lowbias32" of C. Wellons's
// hash-prospector (2020), an xorshift-multiply chain. Mirrored in
// shaders/common.glsl.
int qualitative_index(std::uint32_t k) {
  std::uint32_t x = k;
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return static_cast<int>(2 * (x % (kQualitative / 2)) + (k & 1));
}

Color colormap_color(ColorMap map, double t) {
  if (map == ColorMap::Qualitative) {
    const double k = std::isfinite(t) ? std::floor(t + 0.5) : 0.0;
    // identities beyond 2^31 wrap (the renderer's float values hold 2^24 exactly)
    const auto id = static_cast<std::uint32_t>(static_cast<std::int64_t>(std::fmod(k, 4294967296.0)));
    return qualitative_color(qualitative_index(id));
  }
  if (map == ColorMap::Categorical) {
    if (!std::isfinite(t)) return categorical_colors()[0];
    double k = std::fmod(std::floor(t + 0.5), 8.0);
    if (k < 0) k += 8;
    return categorical_colors()[static_cast<int>(k) & 7];
  }
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  switch (map) {
    case ColorMap::Diverging:
      return from_lab(cool_warm(t));
    case ColorMap::Force:
      return from_lab(ramp(kForce, t));
    case ColorMap::Glow:
      return from_lab(ramp(kForce, 1 - t));
    case ColorMap::Sequential:
    default:
      return from_lab(viridis(t));
  }
}

std::vector<std::uint8_t> colormap_table(ColorMap map, int entries) {
  std::vector<std::uint8_t> out;
  if (map == ColorMap::Qualitative) {
    for (int k = 0; k < kQualitative; ++k) {
      const Color c = qualitative_color(k);
      out.insert(out.end(), {c.r, c.g, c.b, c.a});
    }
    return out;
  }
  if (map == ColorMap::Categorical) entries = 8;
  if (entries <= 0) return out;
  out.reserve(static_cast<std::size_t>(entries) * 4);
  for (int i = 0; i < entries; ++i) {
    const double t = map == ColorMap::Categorical ? i : entries > 1 ? double(i) / (entries - 1) : 0;
    const Color c = colormap_color(map, t);
    out.insert(out.end(), {c.r, c.g, c.b, c.a});
  }
  return out;
}

std::optional<ColorMap> parse_colormap(std::string_view s) {
  std::string lower(s);
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  for (ColorMap m :
       {ColorMap::Sequential, ColorMap::Diverging, ColorMap::Categorical, ColorMap::Force,
        ColorMap::Glow, ColorMap::Qualitative})
    if (lower == to_string(m)) return m;
  return std::nullopt;
}

const char* to_string(ColorMap map) {
  switch (map) {
    case ColorMap::Sequential: return "sequential";
    case ColorMap::Diverging: return "diverging";
    case ColorMap::Categorical: return "categorical";
    case ColorMap::Force: return "force";
    case ColorMap::Glow: return "glow";
    case ColorMap::Qualitative: return "qualitative";
  }
  return "?";
}

LegendLayout legend_layout(int width, int height, const Legend& legend) {
  const std::optional<Fitted> f = fit_legend(width, height, legend);
  return f ? f->layout : LegendLayout{};
}

Rect draw_legend(Image& img, const Legend& legend) {
  if (img.width <= 0 || img.height <= 0 ||
      img.rgba.size() != static_cast<std::size_t>(img.width) * img.height * 4)
    return {0, 0, 0, 0};
  const std::optional<Fitted> f = fit_legend(img.width, img.height, legend);
  if (!f) return {0, 0, 0, 0};
  const Rect r = f->layout.panel;
  if (r.x1 <= r.x0 || r.y1 <= r.y0) return {0, 0, 0, 0};
  // Draw into a copy of the panel's pixels and write them back: text has no
  // clip rectangle, and this way nothing can land outside `r`.
  Image sub{r.x1 - r.x0, r.y1 - r.y0, {}};
  sub.rgba.resize(static_cast<std::size_t>(sub.width) * sub.height * 4);
  const std::size_t row_bytes = static_cast<std::size_t>(sub.width) * 4;
  for (int y = 0; y < sub.height; ++y)
    std::copy_n(&img.rgba[(static_cast<std::size_t>(r.y0 + y) * img.width + r.x0) * 4], row_bytes,
                &sub.rgba[y * row_bytes]);
  render(sub, legend, f->texts, f->placed);
  for (int y = 0; y < sub.height; ++y)
    std::copy_n(&sub.rgba[y * row_bytes], row_bytes,
                &img.rgba[(static_cast<std::size_t>(r.y0 + y) * img.width + r.x0) * 4]);
  return r;
}

}  // namespace simsols::plot
