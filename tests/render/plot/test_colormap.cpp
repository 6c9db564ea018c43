// Colour maps and the colour legend (render/plot/colormap.h): lightness ordering
// of the sequential and force maps measured in CIELAB from the 8-bit output,
// the sequential map against published viridis colours, the diverging one
// against Moreland's cool-warm table and its neutral, symmetric lightness,
// distinct cycling categories, hashed
// qualitative identities, tables
// equal to the per-value colours, and a legend that stays inside its
// rectangle, shows the map on its bar and goes to the corner asked for.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "render/plot/colormap.h"

namespace simsols::plot {
namespace {

constexpr ColorMap kAllMaps[] = {ColorMap::Sequential, ColorMap::Diverging, ColorMap::Categorical,
                                 ColorMap::Force, ColorMap::Glow, ColorMap::Qualitative};

struct Lab {
  double L, a, b;
};

// CIELAB (D65) of an 8-bit sRGB colour, written out independently of the
// library's own conversion.
Lab to_lab(Color c) {
  const auto lin = [](std::uint8_t v) {
    const double s = v / 255.0;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
  };
  const double r = lin(c.r), g = lin(c.g), b = lin(c.b);
  const double X = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047;
  const double Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double Z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883;
  const auto f = [](double t) {
    return t > 216.0 / 24389 ? std::cbrt(t) : (24389.0 / 27 * t + 16) / 116;
  };
  return {116 * f(Y) - 16, 500 * (f(X) - f(Y)), 200 * (f(Y) - f(Z))};
}

double chroma(const Lab& c) { return std::hypot(c.a, c.b); }
double delta_e(const Lab& p, const Lab& q) { return std::hypot(p.L - q.L, p.a - q.a, p.b - q.b); }
double lightness(ColorMap m, double t) { return to_lab(colormap_color(m, t)).L; }

// L* of the 256 entries of map m rises (rising) or falls strictly.
void expect_lightness_strictly_monotonic(ColorMap m, bool rising) {
  double prev = rising ? -1 : 101;
  for (int i = 0; i < 256; ++i) {
    const double L = lightness(m, i / 255.0);
    if (rising)
      EXPECT_GT(L, prev) << to_string(m) << " at entry " << i;
    else
      EXPECT_LT(L, prev) << to_string(m) << " at entry " << i;
    prev = L;
  }
}

TEST(Colormap, SequentialLightnessStrictlyIncreasingOverWideRange) {
  expect_lightness_strictly_monotonic(ColorMap::Sequential, true);
  EXPECT_LT(lightness(ColorMap::Sequential, 0), 20);
  EXPECT_GT(lightness(ColorMap::Sequential, 1), 85);
}

TEST(Colormap, SequentialEndpointsAndMiddleHaveTheIntendedHues) {
  const Color lo = colormap_color(ColorMap::Sequential, 0);
  EXPECT_GT(lo.b, lo.g + 40);  // dark purple
  EXPECT_GT(lo.r, lo.g + 40);
  EXPECT_GT(lo.b, lo.r);
  const Color mid = colormap_color(ColorMap::Sequential, 0.5);
  EXPECT_GT(mid.g, mid.r + 60);  // teal
  EXPECT_GT(mid.b, mid.r + 60);
  const Color hi = colormap_color(ColorMap::Sequential, 1);
  EXPECT_GT(hi.r, 220);  // yellow
  EXPECT_GT(hi.g, 200);
  EXPECT_LT(hi.b, 140);
  const Color green = colormap_color(ColorMap::Sequential, 0.75);
  EXPECT_GT(green.g, green.r + 60);
  EXPECT_GT(green.g, green.b + 40);
}

// Sequential is viridis (van der Walt & Smith, SciPy 2015). Reference
// colours: the ten of R's viridisLite viridis(10) (t = k / 9), and entries
// of matplotlib's published 256-entry table that lie between the points the
// map is built from (every 15th entry). The map rounds within one level of
// viridis(10); the table entries, rounded to 8 bits, are matched within
// 0.92 ΔE*ab (entry 250, near the yellow end, where the spline is 0.55 from
// the table and rounding adds the rest); the bound is 2.
TEST(Colormap, SequentialIsViridis) {
  const std::uint32_t published[10] = {0x440154, 0x482878, 0x3E4A89, 0x31688E, 0x26828E,
                                       0x1F9E89, 0x35B779, 0x6DCD59, 0xB4DE2C, 0xFDE725};
  for (int k = 0; k < 10; ++k) {
    const Color c = colormap_color(ColorMap::Sequential, k / 9.0);
    EXPECT_NEAR(c.r, int(published[k] >> 16), 2) << "t = " << k << "/9";
    EXPECT_NEAR(c.g, int((published[k] >> 8) & 0xFF), 2) << "t = " << k << "/9";
    EXPECT_NEAR(c.b, int(published[k] & 0xFF), 2) << "t = " << k << "/9";
  }
  struct Entry {
    int index;
    double r, g, b;  // sRGB in [0, 1]
  };
  for (const Entry& e : {Entry{7, 0.276022, 0.044167, 0.370164}, {52, 0.252194, 0.269783, 0.531579},
                         {97, 0.171176, 0.452530, 0.557965}, {142, 0.119699, 0.618490, 0.536347},
                         {187, 0.327796, 0.773980, 0.406640}, {232, 0.762373, 0.876424, 0.137064},
                         {246, 0.906311, 0.894855, 0.098125}, {250, 0.945636, 0.899815, 0.112838}}) {
    const auto q = [](double v) { return static_cast<std::uint8_t>(std::lround(255 * v)); };
    const Lab want = to_lab({q(e.r), q(e.g), q(e.b)});
    EXPECT_LT(delta_e(to_lab(colormap_color(ColorMap::Sequential, e.index / 255.0)), want), 2.0)
        << "entry " << e.index;
  }
}

TEST(Colormap, ForceGetsDarkerAndMoreSaturated) {
  expect_lightness_strictly_monotonic(ColorMap::Force, false);
  const Lab lo = to_lab(colormap_color(ColorMap::Force, 0));
  const Lab hi = to_lab(colormap_color(ColorMap::Force, 1));
  EXPECT_GT(lo.L, 80);
  EXPECT_LT(chroma(lo), 25);  // greyish
  EXPECT_GT(lo.b, 0);         // warm (orange side)
  EXPECT_LT(hi.L, 35);
  EXPECT_GT(chroma(hi) / hi.L, 3 * chroma(lo) / lo.L);  // saturation
  const Color red = colormap_color(ColorMap::Force, 1);
  EXPECT_GT(red.r, 2 * red.g);
  EXPECT_GT(red.r, 2 * red.b);
}

// Glow is the Force map backwards: lighter with the force, entry for entry.
TEST(Colormap, GlowIsTheForceMapReversed) {
  expect_lightness_strictly_monotonic(ColorMap::Glow, true);
  for (int i = 0; i < 256; ++i)
    EXPECT_EQ(colormap_color(ColorMap::Glow, i / 255.0), colormap_color(ColorMap::Force, 1 - i / 255.0));
  EXPECT_EQ(parse_colormap("Glow"), ColorMap::Glow);
}

// Moreland's cool-warm is a grey of L* 88 at its centre and has the same
// L* (37.7) at both ends. Near the centre its lightness changes by only
// ~0.06 L* per entry of a 256-entry table, less than 8-bit rounding can
// always follow: there (within 8 entries of the centre) a rise of up to
// 0.03 L* is allowed, ten times the largest seen (0.0023).
TEST(Colormap, DivergingIsLightAndNeutralInTheMiddleAndSymmetric) {
  const Lab mid = to_lab(colormap_color(ColorMap::Diverging, 0.5));
  EXPECT_NEAR(mid.L, 88.0, 0.15);
  EXPECT_LT(chroma(mid), 1.0);  // grey to one level of rounding (0.64)
  const Color blue = colormap_color(ColorMap::Diverging, 0), red = colormap_color(ColorMap::Diverging, 1);
  EXPECT_GT(blue.b, blue.r + 80);
  EXPECT_GT(red.r, red.b + 80);
  EXPECT_LT(lightness(ColorMap::Diverging, 0), 50);
  EXPECT_LT(lightness(ColorMap::Diverging, 1), 50);
  for (int i = 0; i <= 100; ++i) {
    const double t = i / 200.0;
    EXPECT_NEAR(lightness(ColorMap::Diverging, t), lightness(ColorMap::Diverging, 1 - t), 0.5)
        << "t = " << t;
  }
  // Lightness rises to the centre and falls after it.
  for (int i = 1; i < 256; ++i) {
    const double a = lightness(ColorMap::Diverging, (i - 1) / 255.0),
                 b = lightness(ColorMap::Diverging, i / 255.0);
    const double slack = std::abs(i - 128) <= 8 ? 0.03 : 0;
    if (i <= 127) {
      EXPECT_GT(b, a - slack) << i;
    } else if (i >= 129) {
      EXPECT_LT(b, a + slack) << i;
    }
  }
}

// The 33 colours of the cool-warm table in Moreland (2009), sRGB 0..255 at
// t = k / 32: the map reproduces them within one level (rounding).
TEST(Colormap, DivergingIsMorelandsCoolWarm) {
  const int table[33][3] = {
      {59, 76, 192},   {68, 90, 204},   {77, 104, 215},  {87, 117, 225},  {98, 130, 234},
      {108, 142, 241}, {119, 154, 247}, {130, 165, 251}, {141, 176, 254}, {152, 185, 255},
      {163, 194, 255}, {174, 201, 253}, {184, 208, 249}, {194, 213, 244}, {204, 217, 238},
      {213, 219, 230}, {221, 221, 221}, {229, 216, 209}, {236, 211, 197}, {241, 204, 185},
      {245, 196, 173}, {247, 187, 160}, {247, 177, 148}, {247, 166, 135}, {244, 154, 123},
      {241, 141, 111}, {236, 127, 99},  {229, 112, 88},  {222, 96, 77},   {213, 80, 66},
      {203, 62, 56},   {192, 40, 47},   {180, 4, 38}};
  for (int k = 0; k <= 32; ++k) {
    const Color c = colormap_color(ColorMap::Diverging, k / 32.0);
    EXPECT_NEAR(c.r, table[k][0], 2) << "t = " << k << "/32";
    EXPECT_NEAR(c.g, table[k][1], 2) << "t = " << k << "/32";
    EXPECT_NEAR(c.b, table[k][2], 2) << "t = " << k << "/32";
  }
}

TEST(Colormap, CategoricalColoursAreDistinctAndCycle) {
  for (int i = 0; i < 8; ++i)
    for (int j = i + 1; j < 8; ++j)
      EXPECT_GT(delta_e(to_lab(colormap_color(ColorMap::Categorical, i)),
                        to_lab(colormap_color(ColorMap::Categorical, j))),
                30)
          << i << " vs " << j;
  for (int k = -16; k < 24; ++k)
    EXPECT_EQ(colormap_color(ColorMap::Categorical, k),
              colormap_color(ColorMap::Categorical, ((k % 8) + 8) % 8))
        << k;
  EXPECT_EQ(colormap_color(ColorMap::Categorical, 2.9999999), colormap_color(ColorMap::Categorical, 3));
  EXPECT_EQ(colormap_color(ColorMap::Categorical, 1e12 + 5), colormap_color(ColorMap::Categorical, 5));
  EXPECT_EQ(colormap_color(ColorMap::Categorical, NAN), colormap_color(ColorMap::Categorical, 0));
}

// Qualitative (identities, e.g. grains): 20 well separated colours, none
// lost on the renderer's dark background; k and k + 1 never share one,
// and over many identities every colour is used about equally, with no
// pattern along k (k and k + 2 share a colour about one time in ten).
TEST(Colormap, QualitativeColoursAreDistinctAndHashed) {
  const std::vector<std::uint8_t> t = colormap_table(ColorMap::Qualitative);
  ASSERT_EQ(t.size(), 80u);
  EXPECT_EQ(colormap_table(ColorMap::Qualitative, 256).size(), 80u);
  std::vector<Color> entries;
  for (int k = 0; k < 20; ++k) entries.push_back({t[4 * k], t[4 * k + 1], t[4 * k + 2], t[4 * k + 3]});
  for (int i = 0; i < 20; ++i) {
    EXPECT_EQ(entries[i].a, 255);
    EXPECT_GT(to_lab(entries[i]).L, 30) << "entry " << i;  // background L* ~9
    for (int j = i + 1; j < 20; ++j)
      EXPECT_GT(delta_e(to_lab(entries[i]), to_lab(entries[j])), 15) << i << " vs " << j;
  }
  // within each half (even identities, odd identities) the colours are further apart
  for (int i = 0; i < 20; ++i)
    for (int j = i + 2; j < 20; j += 2)
      EXPECT_GT(delta_e(to_lab(entries[i]), to_lab(entries[j])), 30) << i << " vs " << j;
  std::vector<int> uses(20, 0);
  int same_as_next = 0, same_two_on = 0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const int e = qualitative_index(std::uint32_t(k));
    ASSERT_TRUE(e >= 0 && e < 20);
    EXPECT_EQ(colormap_color(ColorMap::Qualitative, k), entries[e]);
    ++uses[e];
    same_as_next += e == qualitative_index(std::uint32_t(k + 1));
    same_two_on += e == qualitative_index(std::uint32_t(k + 2));
  }
  EXPECT_EQ(same_as_next, 0);
  EXPECT_NEAR(double(same_two_on) / n, 0.1, 0.02);
  for (int e = 0; e < 20; ++e) EXPECT_NEAR(uses[e], n / 20, n / 100) << "entry " << e;
  EXPECT_EQ(colormap_color(ColorMap::Qualitative, 6.9999), colormap_color(ColorMap::Qualitative, 7));
  EXPECT_EQ(colormap_color(ColorMap::Qualitative, NAN), colormap_color(ColorMap::Qualitative, 0));
}

TEST(Colormap, TClampedAndOpaque) {
  for (ColorMap m : {ColorMap::Sequential, ColorMap::Diverging, ColorMap::Force}) {
    EXPECT_EQ(colormap_color(m, -0.5), colormap_color(m, 0)) << to_string(m);
    EXPECT_EQ(colormap_color(m, -1e300), colormap_color(m, 0)) << to_string(m);
    EXPECT_EQ(colormap_color(m, 1.5), colormap_color(m, 1)) << to_string(m);
    EXPECT_EQ(colormap_color(m, INFINITY), colormap_color(m, 1)) << to_string(m);
    EXPECT_EQ(colormap_color(m, NAN), colormap_color(m, 0)) << to_string(m);
    for (int i = 0; i <= 20; ++i) EXPECT_EQ(colormap_color(m, i / 20.0).a, 255);
  }
}

TEST(Colormap, TablesMatchColoursAtTheirSamplePoints) {
  for (ColorMap m : {ColorMap::Sequential, ColorMap::Diverging, ColorMap::Force})
    for (int n : {256, 17, 2}) {
      const std::vector<std::uint8_t> t = colormap_table(m, n);
      ASSERT_EQ(t.size(), 4u * n) << to_string(m);
      for (int i = 0; i < n; ++i) {
        const Color c = colormap_color(m, double(i) / (n - 1));
        EXPECT_EQ((Color{t[4 * i], t[4 * i + 1], t[4 * i + 2], t[4 * i + 3]}), c)
            << to_string(m) << " entry " << i << " of " << n;
      }
    }
  const std::vector<std::uint8_t> cat = colormap_table(ColorMap::Categorical);
  ASSERT_EQ(cat.size(), 32u);
  for (int k = 0; k < 8; ++k)
    EXPECT_EQ((Color{cat[4 * k], cat[4 * k + 1], cat[4 * k + 2], cat[4 * k + 3]}),
              colormap_color(ColorMap::Categorical, k));
  EXPECT_EQ(colormap_table(ColorMap::Categorical, 256).size(), 32u);
  EXPECT_TRUE(colormap_table(ColorMap::Sequential, 0).empty());
  EXPECT_EQ(colormap_table(ColorMap::Sequential, 1).size(), 4u);
}

TEST(Colormap, NamesRoundTrip) {
  for (ColorMap m : kAllMaps) {
    EXPECT_EQ(parse_colormap(to_string(m)), m);
    std::string upper = to_string(m);
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_EQ(parse_colormap(upper), m);
  }
  EXPECT_EQ(parse_colormap("viridis"), std::nullopt);
  EXPECT_EQ(parse_colormap(""), std::nullopt);
}

// ---- legend -----------------------------------------------------------------

// A background where every pixel differs from its neighbours, so any stray
// write shows.
Image patterned(int w, int h) {
  Image img = make_image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = &img.rgba[(static_cast<std::size_t>(y) * w + x) * 4];
      p[0] = static_cast<std::uint8_t>(x * 3 + y);
      p[1] = static_cast<std::uint8_t>(y * 5 + x / 2);
      p[2] = static_cast<std::uint8_t>((x ^ y) * 7);
    }
  return img;
}

bool inside(const Rect& r, int x, int y) { return x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1; }

// Checks r lies in the image and that only pixels inside r changed; returns
// how many did.
int changed_only_inside(const Image& before, const Image& after, const Rect& r) {
  EXPECT_GE(r.x0, 0);
  EXPECT_GE(r.y0, 0);
  EXPECT_LE(r.x1, after.width);
  EXPECT_LE(r.y1, after.height);
  int changed = 0, stray = 0;
  for (int y = 0; y < after.height; ++y)
    for (int x = 0; x < after.width; ++x)
      if (pixel(before, x, y) != pixel(after, x, y)) (inside(r, x, y) ? changed : stray)++;
  EXPECT_EQ(stray, 0);
  return changed;
}

Legend force_legend() {
  Legend lg;
  lg.title = "normal force (N)";
  lg.map = ColorMap::Force;
  lg.min = 0;
  lg.max = 37.5;
  return lg;
}

TEST(Legend, ChangesPixelsOnlyInsideItsRectangleInEveryCorner) {
  for (auto corner : {Legend::Corner::TopLeft, Legend::Corner::TopRight,
                      Legend::Corner::BottomLeft, Legend::Corner::BottomRight}) {
    const Image before = patterned(640, 420);
    Image img = before;
    Legend lg = force_legend();
    lg.corner = corner;
    const Rect r = draw_legend(img, lg);
    ASSERT_GT(r.x1, r.x0);
    ASSERT_GT(r.y1, r.y0);
    EXPECT_GT(changed_only_inside(before, img, r), (r.x1 - r.x0) * (r.y1 - r.y0) / 2);
    const bool left = corner == Legend::Corner::TopLeft || corner == Legend::Corner::BottomLeft;
    const bool top = corner == Legend::Corner::TopLeft || corner == Legend::Corner::TopRight;
    if (left) {
      EXPECT_LT(r.x0, 40);
    } else {
      EXPECT_GT(r.x1, img.width - 40);
    }
    if (top) {
      EXPECT_LT(r.y0, 40);
    } else {
      EXPECT_GT(r.y1, img.height - 40);
    }
    EXPECT_LT(r.x1 - r.x0, img.width / 2);  // a corner, not the whole frame
    const LegendLayout L = legend_layout(img.width, img.height, lg);
    EXPECT_EQ(L.panel.x0, r.x0);
    EXPECT_EQ(L.panel.y1, r.y1);
  }
}

TEST(Legend, BarFollowsTheColourMap) {
  for (ColorMap m : {ColorMap::Sequential, ColorMap::Diverging, ColorMap::Force}) {
    Image img = make_image(900, 700, {30, 30, 30});
    Legend lg;
    lg.title = "speed (m/s)";
    lg.map = m;
    lg.min = -0.2;
    lg.max = 1.7;
    lg.corner = Legend::Corner::BottomLeft;
    const Rect r = draw_legend(img, lg);
    const LegendLayout L = legend_layout(img.width, img.height, lg);
    const Rect b = L.bar;
    ASSERT_GE(b.y1 - b.y0, 100) << to_string(m);  // a bar one can read
    ASSERT_GE(b.x1 - b.x0, 8);
    ASSERT_TRUE(inside(r, b.x0, b.y0) && inside(r, b.x1 - 1, b.y1 - 1));
    const int x = (b.x0 + b.x1) / 2;
    for (int y = b.y0; y < b.y1; y += 7) {
      const double t = double(b.y1 - 1 - y) / (b.y1 - b.y0 - 1);
      const Color want = colormap_color(m, t), got = pixel(img, x, y);
      EXPECT_NEAR(got.r, want.r, 2) << to_string(m) << " row " << y;
      EXPECT_NEAR(got.g, want.g, 2) << to_string(m) << " row " << y;
      EXPECT_NEAR(got.b, want.b, 2) << to_string(m) << " row " << y;
    }
    EXPECT_EQ(pixel(img, x, b.y0), colormap_color(m, 1));  // max at the top
    EXPECT_EQ(pixel(img, x, b.y1 - 1), colormap_color(m, 0));
  }
}

TEST(Legend, CategoricalSwatchesShowTheCategories) {
  Image img = make_image(800, 600);
  Legend lg;
  lg.title = "species";
  lg.map = ColorMap::Categorical;
  lg.min = 3;
  lg.max = 7;
  lg.category_labels = {"sand", "gravel"};
  lg.dark = true;
  const Rect r = draw_legend(img, lg);
  const LegendLayout L = legend_layout(img.width, img.height, lg);
  ASSERT_EQ(L.swatches.size(), 5u);
  for (std::size_t k = 0; k < L.swatches.size(); ++k) {
    const Rect& s = L.swatches[k];
    ASSERT_TRUE(inside(r, s.x0, s.y0) && inside(r, s.x1 - 1, s.y1 - 1));
    EXPECT_EQ(pixel(img, (s.x0 + s.x1) / 2, (s.y0 + s.y1) / 2),
              colormap_color(ColorMap::Categorical, 3 + k));
    if (k > 0) {
      EXPECT_GT(s.y0, L.swatches[k - 1].y1);  // top to bottom, apart
    }
  }
}

// A qualitative legend shows its colours as a strip and its note, no values.
TEST(Legend, QualitativeStripAndNote) {
  Image img = make_image(800, 600);
  Legend lg;
  lg.title = "grain";
  lg.note = "one colour per grain";
  lg.map = ColorMap::Qualitative;
  lg.min = 0;
  lg.max = 5000;
  lg.dark = true;
  const Rect r = draw_legend(img, lg);
  const LegendLayout L = legend_layout(img.width, img.height, lg);
  const std::vector<std::uint8_t> t = colormap_table(ColorMap::Qualitative);
  ASSERT_EQ(L.swatches.size(), 20u);
  for (std::size_t k = 0; k < L.swatches.size(); ++k) {
    const Rect& s = L.swatches[k];
    ASSERT_TRUE(inside(r, s.x0, s.y0) && inside(r, s.x1 - 1, s.y1 - 1));
    EXPECT_EQ(pixel(img, (s.x0 + s.x1) / 2, (s.y0 + s.y1) / 2),
              (Color{t[4 * k], t[4 * k + 1], t[4 * k + 2], 255}));
    if (k > 0) {
      EXPECT_EQ(s.x0, L.swatches[k - 1].x1);  // left to right, side by side
    }
  }
  // the note sits under the strip: some text-coloured pixels there
  int ink = 0;
  for (int y = L.bar.y1 + 2; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) ink += pixel(img, x, y).r > 200;
  EXPECT_GT(ink, 50);
  // no value labels: the panel is no taller than title, strip, note and padding
  EXPECT_LT(r.y1 - r.y0, 4 * (L.bar.y1 - L.bar.y0) + 40);
}

TEST(Legend, TinyImagesGetNothing) {
  for (auto [w, h] : {std::pair{119, 119}, {100, 800}, {800, 100}, {1, 1}}) {
    const Image before = patterned(w, h);
    Image img = before;
    const Rect r = draw_legend(img, force_legend());
    EXPECT_EQ(r.x1 - r.x0, 0);
    EXPECT_EQ(r.y1 - r.y0, 0);
    EXPECT_EQ(img.rgba, before.rgba) << w << " x " << h;
  }
  Image empty;
  const Rect r = draw_legend(empty, force_legend());
  EXPECT_EQ(r.x1 - r.x0, 0);
  EXPECT_TRUE(empty.rgba.empty());
}

TEST(Legend, SmallImagesAndLongTitlesStayInside) {
  for (auto [w, h] : {std::pair{120, 120}, {160, 400}, {400, 130}, {1920, 1080}}) {
    Legend lg = force_legend();
    lg.title = "a very long title that would never fit into a small frame at all";
    for (auto corner : {Legend::Corner::TopLeft, Legend::Corner::BottomRight}) {
      lg.corner = corner;
      const Image before = patterned(w, h);
      Image img = before;
      const Rect r = draw_legend(img, lg);
      ASSERT_GT(r.x1, r.x0) << w << " x " << h;
      EXPECT_GT(changed_only_inside(before, img, r), 0);
    }
  }
}

TEST(Legend, ScalesWithTheImageAndTheScaleFactor) {
  const Legend lg = force_legend();
  const LegendLayout small = legend_layout(1200, 1000, lg), big = legend_layout(2400, 2000, lg);
  EXPECT_NEAR(double(big.bar.y1 - big.bar.y0) / (small.bar.y1 - small.bar.y0), 2.0, 0.05);
  Legend half = lg;
  half.scale = 0.5;
  const LegendLayout h = legend_layout(1200, 1000, half);
  EXPECT_NEAR(double(h.bar.y1 - h.bar.y0) / (small.bar.y1 - small.bar.y0), 0.5, 0.05);
}

TEST(Legend, DegenerateRangesStillDraw) {
  for (auto [lo, hi] : {std::pair{2.0, 2.0}, {5.0, -5.0}, {NAN, 1.0}, {0.0, 1e-12}, {-1e9, 3e9}}) {
    Legend lg;
    lg.title = "value";
    lg.min = lo;
    lg.max = hi;
    const Image before = patterned(500, 500);
    Image img = before;
    const Rect r = draw_legend(img, lg);
    ASSERT_GT(r.x1, r.x0);
    EXPECT_GT(changed_only_inside(before, img, r), 0);
  }
}

}  // namespace
}  // namespace simsols::plot
