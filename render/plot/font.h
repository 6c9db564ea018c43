// Text for charts and legends: DejaVu Sans (Debian's fonts-dejavu-core)
// rasterised by FreeType (libfreetype-dev) into image.h's Image.
//
// The font file is looked for at run time in a fixed list of standard
// places (Debian's /usr/share/fonts/truetype/dejavu/ first, then the
// folders other distributions use); when none has it, every call throws a
// std::runtime_error that names the path and the package to install.
//
// How a string is drawn: UTF-8 is decoded (a malformed sequence becomes
// U+FFFD), each code point mapped to its glyph (one the font lacks is drawn
// as the font's missing-glyph box), and the glyphs placed along the
// baseline by their unhinted advances plus the font's kerning pairs
// (FT_Get_Kerning: "AV" sits closer than A and V apart), at fractional
// pixel positions. Each outline is rendered to 8-bit antialiased coverage;
// the coverages of a string are summed into one mask and blended once with
// the colour (its alpha multiplies the coverage), so touching glyphs never
// darken each other. A rotated string is the same outlines turned a
// quarter turn before rendering, so it is as sharp as a level one.
//
// Metrics, for a size size_px = the em (DejaVu's units per em):
//   cap height  0.729 em (the height of "H"; digits are as tall),
//   descent     0.236 em (the font's descender: "g", "p", "y", "|" reach it),
// and the ascenders of lowercase letters and brackets ("d", "l", "(") rise
// up to 0.04 em above the cap height. Widths are of the ink: from the left
// edge of the first glyph's ink to the right edge of the last's (a space
// counts as its advance), so alignment is on what is seen.
//
// The FreeType library and faces are opened once, on the first call, and
// shared by every thread behind a mutex (charts are drawn from the study's
// worker threads); nothing else is global.
#pragma once

#include <string>
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

// Draws `utf8` with its anchor point at (x, y). size_px is the em (the
// cap height is 0.729 of it). rotate90 turns the text a quarter turn
// counter-clockwise (reads bottom to top, for y-axis labels); the anchor is
// then taken along the rotated text. weight above 1.2 draws DejaVu Sans
// Bold; other weights embolden (or thin, below 1) the regular face by
// (weight - 1) x 0.085 em of stem width. Returns the ink width in pixels
// (= text_width, except for the bold face, which is wider). Sizes outside
// (0, 4096] draw nothing and return 0.
double draw_text(Image& img, double x, double y, std::string_view utf8, double size_px, Color color,
                 Anchor anchor = {}, bool rotate90 = false, double weight = 1.0);

// Width in pixels from the first glyph's left ink edge to the last's right
// ink edge, kerning included (regular face).
double text_width(std::string_view utf8, double size_px);

// Vertical extent in pixels above and below the baseline (cap height, descender).
double text_cap_height(double size_px);
double text_descent(double size_px);

// The DejaVu Sans file the text is drawn with (bold: DejaVu Sans Bold), for
// other users of the same face (the lab's ImGui font atlas). Throws
// std::runtime_error naming the path and the package when it is missing.
std::string text_font_file(bool bold = false);

}  // namespace simsols::plot
