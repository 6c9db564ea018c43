// Text (render/plot/font.h, DejaVu Sans through FreeType): the ink lies in
// the box the metrics report and reaches its sides; every anchor moves that
// box as documented; Greek letters and symbols are real glyphs, not the
// missing-glyph box; kerning pulls "AV" together; a rotated string is the
// level one turned a quarter turn; weight adds ink; threads may draw at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "render/plot/font.h"

namespace simsols::plot {
namespace {

constexpr Color kBlack{0, 0, 0};

// Pixels that differ from the white background (any coverage at all).
struct Ink {
  int count = 0, x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;  // inclusive bounds
  long sum = 0;                                                    // total coverage, levels
};

Ink ink_of(const Image& img) {
  Ink k;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (const int c = 255 - pixel(img, x, y).r; c > 0) {
        ++k.count, k.sum += c;
        k.x0 = std::min(k.x0, x), k.x1 = std::max(k.x1, x);
        k.y0 = std::min(k.y0, y), k.y1 = std::max(k.y1, y);
      }
  return k;
}

// Ascenders ("d", "l") and brackets rise above the cap height by up to 0.04
// em (font.h); antialiasing may touch one more pixel on every side.
double ascender_allowance(double size) { return 0.04 * size + 1; }

TEST(Font, InkLiesInsideTheMeasuredBoxAndReachesItsSides) {
  for (const std::string s : {"Shear stress τ (kPa)", "σ′v = 160 kPa, φ = 35.2°", "gjpqy|[]",
                              "HIX 0123456789", "e – log p′ ×10⁻³ ²"})
    for (double size : {11.0, 18.0, 33.5}) {
      Image img = make_image(900, 120);
      const double x0 = 20.3, y0 = 70.6;
      const double w = draw_text(img, x0, y0, s, size, kBlack);
      EXPECT_DOUBLE_EQ(w, text_width(s, size)) << s;
      const Ink k = ink_of(img);
      ASSERT_GT(k.count, 20) << s;
      EXPECT_GE(k.x0, std::floor(x0) - 1) << s << " at " << size;
      EXPECT_LE(k.x1, x0 + w + 1) << s << " at " << size;
      EXPECT_LE(k.x0, x0 + 1) << s << " at " << size;  // the ink starts at x0 ...
      EXPECT_GE(k.x1, x0 + w - 2) << s << " at " << size;  // ... and fills the width
      EXPECT_GE(k.y0, y0 - text_cap_height(size) - ascender_allowance(size)) << s;
      EXPECT_LE(k.y1, y0 + text_descent(size) + 1) << s << " at " << size;
    }
}

TEST(Font, MetricsAreDejaVuSans) {
  // DejaVu Sans: units per em 2048, "H" 1493 high, descender 483 (its hhea).
  EXPECT_NEAR(text_cap_height(2048), 1493, 0.5);
  EXPECT_NEAR(text_descent(2048), 483, 0.5);
  // Digits are as tall as capitals: a digit's ink spans the cap height.
  Image img = make_image(200, 200);
  draw_text(img, 10, 150, "8", 100, kBlack);
  const Ink k = ink_of(img);
  EXPECT_NEAR(150 - k.y0, text_cap_height(100), 2.5);
  EXPECT_NEAR(k.y1 + 1, 150, 2.5);  // digits sit on the baseline
}

TEST(Font, AnchorsMoveTheBoxAsDocumented) {
  const std::string s = "HHH";  // flat top and bottom: the ink box is the cap box
  const double size = 40, x = 200, y = 100;
  const double w = text_width(s, size), cap = text_cap_height(size), d = text_descent(size);
  struct Case {
    Anchor a;
    double left, baseline;
  };
  for (const Case& c : {Case{{HAlign::left, VAlign::baseline}, x, y},
                        Case{{HAlign::center, VAlign::top}, x - w / 2, y + cap},
                        Case{{HAlign::right, VAlign::middle}, x - w, y + cap / 2},
                        Case{{HAlign::center, VAlign::bottom}, x - w / 2, y - d}}) {
    Image img = make_image(400, 200);
    draw_text(img, x, y, s, size, kBlack, c.a);
    const Ink k = ink_of(img);
    EXPECT_NEAR(k.x0, c.left, 1.0);
    EXPECT_NEAR(k.x1 + 1, c.left + w, 1.0);
    EXPECT_NEAR(k.y1 + 1, c.baseline, 1.0);
    EXPECT_NEAR(k.y0, c.baseline - cap, 1.0);
  }
}

// The images of one string drawn alone at a fixed place.
Image glyph_image(const std::string& s) {
  Image img = make_image(60, 60);
  draw_text(img, 10, 45, s, 40, kBlack);
  return img;
}

int differing_pixels(const Image& a, const Image& b) {
  int n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) n += std::abs(pixel(a, x, y).r - pixel(b, x, y).r) > 64;
  return n;
}

TEST(Font, GreekLettersAndSymbolsAreRealGlyphs) {
  // U+E000 (private use) is not in DejaVu Sans: it draws the missing-glyph box.
  const Image box = glyph_image("\xEE\x80\x80");
  ASSERT_GT(ink_of(box).count, 50);
  const std::vector<std::string> symbols = {"σ", "τ", "φ", "ψ", "δ", "ε", "θ", "Δ", "μ",
                                            "°", "²", "³", "′", "±", "×", "−", "⁻", "₃"};
  std::vector<Image> images;
  for (const std::string& s : symbols) {
    images.push_back(glyph_image(s));
    EXPECT_GT(ink_of(images.back()).count, 10) << s;
    EXPECT_GT(differing_pixels(images.back(), box), 40) << s << " looks like the missing-glyph box";
  }
  for (std::size_t i = 0; i < images.size(); ++i)
    for (std::size_t j = i + 1; j < images.size(); ++j)
      EXPECT_GT(differing_pixels(images[i], images[j]), 20) << symbols[i] << " vs " << symbols[j];
  // Malformed UTF-8 draws U+FFFD, which the font has: not the missing box either.
  EXPECT_GT(differing_pixels(glyph_image("\xff"), box), 40);
  EXPECT_GT(text_width("\xff\xfe", 16), 0);
  EXPECT_DOUBLE_EQ(text_width("", 16), 0);
}

TEST(Font, KerningPullsAVTogether) {
  // A and V have side bearings of 16 units of DejaVu's 2048 to the em, so
  // without kerning the ink of "AV" would be 32 units (1.6 px at 100 px)
  // wider than A's and V's inks side by side. DejaVu kerns the pair by -130
  // units (-6.3 px): the inks overlap by 4.8 px.
  const double size = 100;
  const double apart = text_width("A", size) + text_width("V", size);
  EXPECT_LT(text_width("AV", size), apart - 4.3);
  EXPECT_GT(text_width("AV", size), apart - 5.3);
  // A pair the font does not kern keeps the letters apart.
  EXPECT_GE(text_width("HH", size), 2 * text_width("H", size));
  // The drawn ink follows the kerned width.
  Image img = make_image(300, 150);
  const double w = draw_text(img, 20, 120, "AV", size, kBlack);
  const Ink k = ink_of(img);
  EXPECT_NEAR(k.x1 + 1 - k.x0, w, 2.0);
}

TEST(Font, Rotate90SwapsTheBoxAndTurnsTheSameRaster) {
  const std::string s = "Shear τ (kPa)";
  const double size = 22;
  Image level = make_image(260, 60), turned = make_image(60, 260);
  const double w = draw_text(level, 10, 40, s, size, kBlack);
  EXPECT_DOUBLE_EQ(draw_text(turned, 40, 250, s, size, kBlack, {}, true), w);
  const Ink a = ink_of(level), b = ink_of(turned);
  // The text reads upwards from the anchor, its top to the left.
  EXPECT_EQ(b.x1 - b.x0, a.y1 - a.y0);
  EXPECT_EQ(b.y1 - b.y0, a.x1 - a.x0);
  EXPECT_NEAR(b.y1 + 1, 250, 1.0);
  EXPECT_GE(b.y0, 250 - w - 1);
  EXPECT_GE(b.x0, 40 - text_cap_height(size) - ascender_allowance(size));
  EXPECT_LE(b.x1, 40 + text_descent(size) + 1);
  // Pixel (x, y) of the level ink is pixel (y, -x) of the turned ink, up to
  // 1/64 px of rounding in where each glyph is placed.
  int worst = 0;
  for (int y = a.y0; y <= a.y1; ++y)
    for (int x = a.x0; x <= a.x1; ++x) {
      const int tx = b.x0 + (y - a.y0), ty = b.y1 - (x - a.x0);
      worst = std::max(worst, std::abs(pixel(level, x, y).r - pixel(turned, tx, ty).r));
    }
  EXPECT_LE(worst, 8);
  EXPECT_EQ(a.count, b.count);
}

TEST(Font, WeightAddsInkAndBoldIsTheBoldFace) {
  const auto ink_at = [](double weight) {
    Image img = make_image(400, 60);
    draw_text(img, 10, 45, "Weight of text", 30, kBlack, {}, false, weight);
    return ink_of(img).sum;
  };
  const long thin = ink_at(0.7), regular = ink_at(1.0), heavier = ink_at(1.15), bold = ink_at(1.25);
  EXPECT_LT(thin, 0.9 * regular);
  EXPECT_GT(heavier, 1.05 * regular);
  EXPECT_GT(bold, 1.3 * regular);  // DejaVu Sans Bold's stems are ~1.6 times as wide
  // The bold face is also wider, and draw_text returns its width.
  Image img = make_image(400, 60);
  EXPECT_GT(draw_text(img, 10, 45, "Weight of text", 30, kBlack, {}, false, 1.25),
            1.05 * text_width("Weight of text", 30));
}

TEST(Font, ColourAlphaAndClipping) {
  Image img = make_image(100, 40);
  draw_text(img, 5, 30, "Hi", 30, {200, 0, 0, 128});
  int reddish = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Color c = pixel(img, x, y);
      EXPECT_GE(c.r, 200);       // half-transparent red over white never gets darker red
      reddish += c.g < 160;      // the full-coverage pixels are half-way to red
      EXPECT_GE(c.g, 255 / 2 - 1);
    }
  EXPECT_GT(reddish, 20);
  // Text running off the image is cut, not wrapped or crashed.
  Image small = make_image(30, 20);
  draw_text(small, -10, 15, "Long text off both sides", 20, kBlack);
  draw_text(small, 10, 1e9, "far away", 20, kBlack);
  EXPECT_GT(ink_of(small).count, 10);
  EXPECT_EQ(draw_text(small, 0, 10, "x", 0, kBlack), 0);
  EXPECT_EQ(draw_text(small, 0, 10, "x", NAN, kBlack), 0);
}

TEST(Font, ThreadsDrawTheSameTextAtOnce) {
  const auto draw = [](int k) {
    Image img = make_image(300, 60);
    draw_text(img, 5, 40, "σ′ = " + std::to_string(k) + " kPa, AV", 14 + k, kBlack, {}, false,
              k % 2 ? 1.3 : 1.0);
    return img;
  };
  std::vector<Image> serial, parallel(8);
  for (int k = 0; k < 8; ++k) serial.push_back(draw(k));
  {
    std::vector<std::thread> threads;
    for (int k = 0; k < 8; ++k)
      threads.emplace_back([&, k] {
        for (int rep = 0; rep < 20; ++rep) parallel[k] = draw(k);
      });
    for (auto& t : threads) t.join();
  }
  for (int k = 0; k < 8; ++k) EXPECT_EQ(parallel[k].rgba, serial[k].rgba) << k;
}

TEST(Font, TheFontFileIsNamed) {
  const std::string regular = text_font_file(), bold = text_font_file(true);
  EXPECT_NE(regular.find("DejaVuSans.ttf"), std::string::npos) << regular;
  EXPECT_NE(bold.find("DejaVuSans-Bold.ttf"), std::string::npos) << bold;
}

}  // namespace
}  // namespace simsols::plot
