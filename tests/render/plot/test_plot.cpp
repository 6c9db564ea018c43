// simsols_plot: PNG round trips and headers, 1-2-5 ticks, a chart's series
// on the expected pixel row and clipped to the plot area, text within its
// reported width, atomic PNG writes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "solver/common/errors.h"
#include "render/plot/chart.h"
#include "render/plot/font.h"
#include "render/plot/png.h"

namespace simsols::plot {
namespace {

namespace fs = std::filesystem;

// CRC-32 as the PNG specification defines it (bitwise, no table).
std::uint32_t crc32_spec(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xFFFFFFFFu;
}

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}

// Gradients, noise and flat areas so every filter type has work to do.
Image varied_image(int w, int h) {
  Image img = make_image(w, h);
  unsigned seed = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      seed = seed * 1103515245u + 12345u;
      std::uint8_t* p = &img.rgba[(static_cast<std::size_t>(y) * w + x) * 4];
      p[0] = static_cast<std::uint8_t>(x * 7 + y);
      p[1] = y < h / 2 ? static_cast<std::uint8_t>(y * 3) : static_cast<std::uint8_t>(seed >> 16);
      p[2] = x < w / 3 ? 200 : static_cast<std::uint8_t>((x ^ y) * 5);
      p[3] = static_cast<std::uint8_t>(255 - (x + y) % 97);
    }
  return img;
}

fs::path temp_dir() {
  const fs::path d =
      fs::temp_directory_path() / ("simsols_test_plot_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

TEST(Png, RoundTrip) {
  for (const Image& img : {varied_image(37, 23), varied_image(300, 17), make_image(1, 1, {1, 2, 3, 4})}) {
    const Image back = decode_png(encode_png(img));
    EXPECT_EQ(back.width, img.width);
    EXPECT_EQ(back.height, img.height);
    EXPECT_EQ(back.rgba, img.rgba);
  }
}

TEST(Png, SignatureAndHeader) {
  const std::string png = encode_png(varied_image(300, 17));
  ASSERT_GT(png.size(), 8u + 25 + 12 + 12);
  const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(static_cast<unsigned char>(png[i]), sig[i]);
  EXPECT_EQ(be32(png, 8), 13u);
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(be32(png, 16), 300u);
  EXPECT_EQ(be32(png, 20), 17u);
  EXPECT_EQ(png[24], 8);  // bit depth
  EXPECT_EQ(png[25], 6);  // RGBA
  EXPECT_EQ(png[26], 0);
  EXPECT_EQ(png[27], 0);
  EXPECT_EQ(png[28], 0);  // not interlaced
  EXPECT_EQ(be32(png, 29), crc32_spec(png.substr(12, 17)));
  EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND");
}

TEST(Png, RejectsCorruptData) {
  std::string png = encode_png(varied_image(8, 8));
  EXPECT_THROW(decode_png(png.substr(0, png.size() / 2)), ReadError);
  png[25] = 5;  // IHDR: no such colour type
  EXPECT_THROW(decode_png(png), ReadError);
  EXPECT_THROW(decode_png("not a png"), ReadError);
}

TEST(Png, WriteIsAtomicAndNamesThePathOnFailure) {
  const fs::path dir = temp_dir();
  const std::string path = (dir / "image.png").string();
  const Image img = varied_image(20, 10);
  write_png(img, path);
  EXPECT_TRUE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(read_png(path).rgba, img.rgba);

  const std::string bad = (dir / "no_such_dir" / "image.png").string();
  try {
    write_png(img, bad);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(bad + ".tmp"));
  fs::remove_all(dir);
}

TEST(Ticks, OneTwoFiveStepsCoverTheRange) {
  const double cases[][2] = {{0, 1},     {0, 10},    {-3.7, 12.2}, {0.001, 0.0047},
                             {100, 1e4}, {-50, -20}, {0, 0.3},     {2.5, 2.6}};
  for (const auto& c : cases)
    for (int n : {3, 5, 8}) {
      const auto t = nice_ticks(c[0], c[1], n);
      ASSERT_GE(t.size(), 2u) << c[0] << " " << c[1] << " " << n;
      EXPECT_LE(t.size(), static_cast<std::size_t>(n) + 1);
      const double step = t[1] - t[0];
      const double mant = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
      EXPECT_TRUE(std::abs(mant - 1) < 1e-6 || std::abs(mant - 2) < 1e-6 ||
                  std::abs(mant - 5) < 1e-6)
          << "step " << step;
      for (std::size_t i = 1; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], step, step * 1e-6);
      const double eps = step * 1e-6;
      EXPECT_GE(t.front(), c[0] - eps);
      EXPECT_LE(t.back(), c[1] + eps);
      EXPECT_LT(t.front() - c[0], step);
      EXPECT_LT(c[1] - t.back(), step);
    }
  EXPECT_EQ(nice_ticks(0, 1, 5), (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1}));
  EXPECT_EQ(nice_ticks(4, 4, 5).size(), 1u);
  EXPECT_TRUE(nice_ticks(0, std::numeric_limits<double>::quiet_NaN(), 5).empty());
  EXPECT_EQ(format_tick(0.1 + 0.2, 0.1), "0.3");
  EXPECT_EQ(format_tick(-1e-17, 0.1), "0.0");
  EXPECT_EQ(format_tick(150, 50), "150");
  EXPECT_EQ(format_tick(0.25, 0.05), "0.25");
  EXPECT_EQ(tick_labels({0, 1e7, 2.5e7}, 5e6), (std::vector<std::string>{"0", "1×10⁷", "2.5×10⁷"}));
  EXPECT_EQ(tick_labels({-1e-5, 0, 3e-5}, 1e-5),
            (std::vector<std::string>{"-1×10⁻⁵", "0", "3×10⁻⁵"}));
  EXPECT_EQ(tick_labels({0.1, 0.10000005}, 5e-8),
            (std::vector<std::string>{"0.10000000", "0.10000005"}));
}

bool near_color(const Image& img, int x, int y, Color c, int tol) {
  const Color p = pixel(img, x, y);
  return std::abs(p.r - c.r) <= tol && std::abs(p.g - c.g) <= tol && std::abs(p.b - c.b) <= tol;
}

TEST(Chart, HorizontalSeriesOnItsRowAndInsideThePlotArea) {
  Chart c;
  c.title = "Flat";
  c.x_label = "x";
  c.y_label = "y";
  c.legend = false;
  Series s;
  s.label = "y = 1";
  for (int i = 0; i <= 10; ++i) s.x.push_back(i), s.y.push_back(1.0);
  c.series.push_back(s);
  const ChartLayout L = chart_layout(c);
  EXPECT_DOUBLE_EQ(L.x_lo, 0);
  EXPECT_DOUBLE_EQ(L.x_hi, 10);
  EXPECT_LT(L.y_lo, 1);  // flat range padded
  EXPECT_GT(L.y_hi, 1);
  const Image img = render_chart(c);
  ASSERT_EQ(img.width, 1200);
  ASSERT_EQ(img.height, 800);
  const Color col = palette_color(0);

  const int row = static_cast<int>(std::floor(L.py(1.0)));
  int on_row = 0;
  for (int x = L.left; x < L.right; ++x) on_row += near_color(img, x, row, col, 2);
  EXPECT_GT(on_row, 0.95 * (L.right - L.left));

  // The row found by searching agrees with the layout.
  int best_row = -1, best = 0;
  for (int y = L.top; y < L.bottom; ++y) {
    int n = 0;
    for (int x = L.left; x < L.right; ++x) n += near_color(img, x, y, col, 2);
    if (n > best) best = n, best_row = y;
  }
  EXPECT_LE(std::abs(best_row - row), 1);

  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (x >= L.left && x < L.right && y >= L.top && y < L.bottom) continue;
      ASSERT_FALSE(near_color(img, x, y, col, 60)) << "series colour outside at " << x << "," << y;
    }
}

TEST(Chart, DegenerateInputsDoNotCrash) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Chart c;
  EXPECT_EQ(render_chart(c, 300, 200).width, 300);  // nothing at all
  c.series.push_back({"empty", {}, {}, {}});
  c.series.push_back({"all NaN", {nan, nan}, {nan, nan}, {}});
  c.series.push_back({"one point", {2}, {3}, {}, true, true});
  c.series.push_back({"mismatched", {0, 1, 2, 3}, {1, nan, 2}, {}, true, false, true});
  c.markers.push_back({nan, 1, "nowhere"});
  c.markers.push_back({1, 2, "peak"});
  EXPECT_EQ(render_chart(c, 400, 300).height, 300);
  c.x_min = 5, c.x_max = 5;  // degenerate user limits
  c.y_min = 10, c.y_max = -10;
  const ChartLayout L = chart_layout(c, 400, 300);
  EXPECT_LT(L.x_lo, L.x_hi);
  EXPECT_LT(L.y_lo, L.y_hi);
  EXPECT_NO_THROW(render_chart(c, 400, 300));
  EXPECT_THROW(render_chart(c, 10, 10), std::invalid_argument);
}

TEST(Chart, NanBreaksTheLine) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Chart c;
  c.legend = false;
  c.series.push_back({"", {0, 4, 5, 6, 10}, {1, 1, nan, 1, 1}, Color{200, 0, 0}});
  c.y_min = 0, c.y_max = 2;
  const ChartLayout L = chart_layout(c);
  const Image img = render_chart(c);
  const int row = static_cast<int>(std::floor(L.py(1.0)));
  const Color red{200, 0, 0};
  EXPECT_TRUE(near_color(img, static_cast<int>(L.px(2)), row, red, 2));
  EXPECT_TRUE(near_color(img, static_cast<int>(L.px(8)), row, red, 2));
  EXPECT_FALSE(near_color(img, static_cast<int>(L.px(5)), row, red, 60));
}

// An e-log sigma' axis: ticks at 1, 2 and 5 x 10^k labelled by value, the
// points evenly spaced by decade, and a point at x <= 0 left out as a NaN
// would be (it breaks the line instead of running it off the left edge).
TEST(Chart, LogAxisTicksDecadesAndLeavesOutNonPositiveX) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Chart c;
  c.legend = false;
  c.x_log = true;
  c.series.push_back({"", {25, 100, 400, 800}, {1, 1, 1, 1}, Color{200, 0, 0}});
  c.y_min = 0, c.y_max = 2;
  const ChartLayout L = chart_layout(c);
  EXPECT_TRUE(L.x_log);
  ASSERT_EQ(L.x_labels.size(), L.x_ticks.size());
  for (const char* label : {"50", "100", "200", "500"})
    EXPECT_NE(std::find(L.x_labels.begin(), L.x_labels.end(), label), L.x_labels.end()) << label;
  EXPECT_NEAR(L.px(100) - L.px(25), L.px(400) - L.px(100), 1e-9);
  EXPECT_TRUE(std::isnan(L.px(0)));
  Chart with_zero = c, with_nan = c;
  with_zero.series[0].x = {25, 0, 400, 800};
  with_nan.series[0].x = {25, nan, 400, 800};
  EXPECT_EQ(render_chart(with_zero).rgba, render_chart(with_nan).rgba);
}

TEST(Text, InkLiesWithinTheReportedWidth) {
  Image img = make_image(400, 120);
  const std::string s = "Shear stress τ (kPa) σ' 45°";
  const double size = 18, x0 = 20, y0 = 60;
  const double w = draw_text(img, x0, y0, s, size, {0, 0, 0});
  EXPECT_DOUBLE_EQ(w, text_width(s, size));
  EXPECT_GT(w, 100);
  EXPECT_LT(w, 380);
  int dark = 0, min_x = img.width, max_x = -1;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (pixel(img, x, y).r < 128) {
        ++dark;
        min_x = std::min(min_x, x), max_x = std::max(max_x, x);
        EXPECT_GE(y, y0 - text_cap_height(size) - 3);
        EXPECT_LE(y, y0 + text_descent(size) + 2);
      }
  EXPECT_GT(dark, 150);
  EXPECT_GE(min_x, x0 - 2);
  EXPECT_LE(max_x, x0 + w + 2);
  EXPECT_GT(max_x, x0 + 0.9 * w);  // the ink spans the width

  // Rotated and right-aligned: the ink runs upwards from the anchor.
  Image rot = make_image(100, 300);
  const double wr =
      draw_text(rot, 50, 280, "τ (kPa)", 16, {0, 0, 0}, {HAlign::left, VAlign::top}, true);
  for (int y = 0; y < rot.height; ++y)
    for (int x = 0; x < rot.width; ++x)
      if (pixel(rot, x, y).r < 128) {
        EXPECT_GE(y, 280 - wr - 2);
        EXPECT_LE(y, 282);
        EXPECT_GE(x, 48);
      }
  EXPECT_DOUBLE_EQ(text_width("", 16), 0);
  EXPECT_GT(text_width("\xff\xfe", 16), 0);  // malformed UTF-8 draws boxes
}

TEST(Image, PrimitivesRespectTheClip) {
  Image img = make_image(50, 50);
  const Rect clip{10, 10, 40, 40};
  draw_line(img, {0, 25}, {50, 25}, 3, {0, 0, 0}, clip);
  fill_circle(img, 10, 10, 8, {0, 0, 0}, clip);
  draw_line(img, {0, 5}, {50, 45}, 2, {0, 0, 0}, clip, Dash{4, 3});
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 50; ++x)
      if (x < 10 || x >= 40 || y < 10 || y >= 40) {
        ASSERT_EQ(pixel(img, x, y), (Color{255, 255, 255}));
      }
  EXPECT_EQ(pixel(img, 25, 25), (Color{0, 0, 0}));
  EXPECT_EQ(pixel(img, 12, 12), (Color{0, 0, 0}));
}

}  // namespace
}  // namespace simsols::plot
