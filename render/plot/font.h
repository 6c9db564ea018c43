// A vector stroke font for chart labels, drawn with image.h's anti-aliased
// polylines, so text needs no font files or font library and scales freely.
//
// Each glyph is a few polylines and elliptical arcs on a small grid (baseline
// y = 0, x-height 7, cap height 10, descender -3; the em is 14 units), kept
// readable as text in font.cpp. It covers ASCII 32-126, the Greek letters of
// geotechnics labels (σ τ φ ψ δ ε θ γ μ ρ ω π Δ) and ° ² ³ ¹ ⁰-⁹ ⁺ ⁻ · ± × −
// – — ′ ‘ ’ “ ”; input is UTF-8 and anything else is drawn as a box.
#pragma once

#include <string_view>

#include "render/plot/image.h"

namespace simsols::plot {

enum class HAlign { left, center, right };
// top: cap height, middle: half cap height (centres digits), bottom: descender.
enum class VAlign { baseline, top, middle, bottom };

struct Anchor {
  HAlign h = HAlign::left;
  VAlign v = VAlign::baseline;
};

// Draws `utf8` with its anchor point at (x, y). size_px is the em (descender
// to ascender; cap height is 10/14 of it). rotate90 turns the text a quarter
// turn counter-clockwise (reads bottom to top, for y-axis labels); the anchor
// is then taken along the rotated text. weight scales the stroke width.
// Returns the advance width in pixels (= text_width).
double draw_text(Image& img, double x, double y, std::string_view utf8, double size_px, Color color,
                 Anchor anchor = {}, bool rotate90 = false, double weight = 1.0);

// Width in pixels from the first glyph's left edge to the last's right edge.
double text_width(std::string_view utf8, double size_px);

// Vertical extent in pixels above and below the baseline (cap height, descender).
double text_cap_height(double size_px);
double text_descent(double size_px);

}  // namespace simsols::plot
