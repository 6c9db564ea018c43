// Colour maps for the 3D renderer (particles coloured by speed, stress,
// force or category) and the colour legend drawn over its frames.
//
// Sequential and Diverging are published perceptual maps and Qualitative a
// published set of colours; Categorical and Force are designed here from a
// few control points in CIELAB (D65). Continuous maps are rounded to 8 bits
// by picking, among the 8 floor/ceil combinations of the channels, the one
// nearest the intended L*, which keeps lightness strictly monotonic even
// between neighbouring entries of a 256-entry table.
//
//   Sequential   viridis: S. van der Walt and N. Smith, "A Better Default
//                Colormap for Matplotlib", SciPy 2015 (matplotlib's default
//                map, dedicated to the public domain, CC0). Dark purple, blue,
//                teal, green, yellow, L* 15 -> 91, designed in CAM02-UCS to be
//                uniform, to read in grey and for the common colour-vision
//                deficiencies. Its published 256-entry table at every 15th
//                entry, joined by a Catmull-Rom spline in CIELAB: every entry
//                of the table is matched within 0.55 ΔE*ab (mean 0.05).
//   Diverging    cool-warm: K. Moreland, "Diverging Color Maps for Scientific
//                Visualization", Advances in Visual Computing (ISVC 2009),
//                LNCS 5876, pp. 92-103. Blue sRGB (59, 76, 192) through a grey
//                (221, 221, 221), L* 88, to red (180, 4, 38), interpolated
//                linearly in the paper's Msh space (magnitude, saturation,
//                hue of CIELAB) with its hue adjustment at the grey; the
//                ends have the same L* (37.7), so neither sign looks stronger.
//                It reproduces the paper's 33-entry table to one level.
//   Categorical  8 colours of similar chroma spread over hue, neighbours far
//                apart in hue and lightness (smallest CIELAB distance ~38);
//                mid lightness, so lit and shaded sides of a sphere both
//                keep their hue.
//   Force        L* 86 -> 27: light greyish orange to dark red, chroma
//                growing with force, so strong chains stand out and weak
//                ones recede. L* runs linearly in t; a* and b* follow a
//                Catmull-Rom spline through the control points. Chains are
//                drawn over beads coloured by viridis or the categorical
//                colours: a red ramp keeps them apart (cividis, the other
//                published sequential map of its kind, runs blue to yellow
//                like viridis).
//   Glow         the Force map reversed (L* 27 -> 86): the force chains on
//                the renderer's dark background, where the weak end of the
//                network recedes into the background and the strong chains
//                stand out light and thick.
//   Qualitative  identities (one colour per grain): 20 of the 22 "colours of
//                maximum contrast" of K. L. Kelly, Color Engineering 3(6),
//                1965 (in their ISCC-NBS centroid sRGB values), without his
//                black and olive green, which vanish on the renderer's dark
//                background. Integer k takes entry 2 (h(k) mod 10) + (k mod 2),
//                h an integer hash (qualitative_index): unrelated colours for
//                k and k + 1, never the same one.
//
// colormap_table gives the renderer the same colours as a 1D texture, so the
// shader and the legend agree to the bit.
//
// The legend is a semi-opaque rounded panel in a corner: the title, a
// vertical colour bar (t = 0 at the bottom) with 1-2-5 ticks from chart.h,
// or one swatch per category, or (Qualitative) a strip of its colours and a
// note in place of values. It is drawn into a copy of its own rectangle that is then written
// back, so no pixel outside the returned rectangle changes, text included.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "render/plot/image.h"

namespace simsols::plot {

enum class ColorMap {
  Sequential,   // viridis: dark purple -> teal -> green -> yellow, lightness increasing
  Diverging,    // Moreland's cool-warm: blue - light grey - red, for signed values
  Categorical,  // 8 distinct colours; category k -> colour k mod 8
  Force,        // light grey-orange -> dark red, darker and more saturated
  Glow,         // Force reversed: dark red -> light grey-orange, for chains on a dark background
  Qualitative,  // 20 distinct colours for identities; k -> colour qualitative_index(k)
};

// Qualitative: the entry (0..19) of identity k (k >= 0; negative k are
// taken as their two's complement). The shaders (shaders/common.glsl)
// compute the same.
int qualitative_index(std::uint32_t k);

// t in [0, 1], clamped (NaN reads as 0). Categorical: t is the category
// index, rounded to the nearest integer, any value (negative ones cycle too).
// Qualitative: t is the identity, rounded to the nearest integer (NaN reads
// as 0).
Color colormap_color(ColorMap map, double t);

// RGBA8, 4 bytes per entry: `entries` samples at t = i / (entries - 1) (one
// entry: t = 0; none for entries <= 0). Categorical: always its 8 colours,
// entry k = category k, whatever `entries` says. Qualitative: its 20
// colours, in entry order, likewise.
std::vector<std::uint8_t> colormap_table(ColorMap map, int entries = 256);

// "sequential", "diverging", "categorical", "force", "glow", "qualitative" (any case).
std::optional<ColorMap> parse_colormap(std::string_view s);
const char* to_string(ColorMap map);

struct Legend {
  std::string title;  // e.g. "speed (m/s)"
  ColorMap map = ColorMap::Sequential;
  // Value range of the bar: min at the bottom, max at the top. Categorical:
  // the categories min..max (integers), one swatch each, min at the top.
  double min = 0, max = 1;
  // Categorical only: category_labels[k] names category min + k; missing
  // labels are the category numbers.
  std::vector<std::string> category_labels;
  // Lines under the bar or the swatches (split at '\n'), e.g. what a
  // Qualitative strip means ("one colour per grain"). Qualitative legends show no values:
  // min and max are not used.
  std::string note;
  enum class Corner { TopLeft, TopRight, BottomLeft, BottomRight } corner = Corner::TopRight;
  double scale = 1;  // 1 = sized for a ~1000 px tall image; scaled with the image
  bool dark = false;  // light text on a dark panel, for dark backgrounds
};

// Where draw_legend puts things, in image pixels. All empty when nothing is
// drawn (an image under 120 px either way).
struct LegendLayout {
  Rect panel{0, 0, 0, 0};  // everything drawn lies inside (clipped to the image)
  // Continuous maps: pixel row y of the bar shows
  // t = (bar.y1 - 1 - y) / (bar.y1 - bar.y0 - 1): t = 1 on the top row, 0 on the bottom one.
  // Categorical: the union of the swatches. Qualitative: the strip.
  Rect bar{0, 0, 0, 0};
  std::vector<Rect> swatches;  // Categorical: category min + k in swatches[k], top to bottom;
                               // Qualitative: entry k in swatches[k], left to right
  double unit = 0;             // pixels per layout unit (1 at 1000 px tall, before fitting)
};

LegendLayout legend_layout(int width, int height, const Legend& legend);

// Draws the legend onto the image; returns the rectangle it covered (empty,
// and nothing drawn, on images under 120 px either way).
Rect draw_legend(Image& img, const Legend& legend);

}  // namespace simsols::plot
