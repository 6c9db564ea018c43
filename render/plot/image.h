// Image: an 8-bit RGBA raster in memory and the few anti-aliased drawing
// primitives that charts and text need (lines, polylines, rectangles, discs,
// rings), all with "source over" blending.
//
// Strokes are rasterised from the exact distance of each pixel centre to the
// segments (coverage = half width + 0.5 - distance, clamped to [0, 1]), with
// round caps and joins. A polyline is accumulated into one coverage mask (the
// maximum over its segments) and blended once, so joins, crossings and dash
// ends never darken. Every primitive takes an optional clip rectangle: the
// chart clips its series to the plot area with it.
//
// No OpenGL, no global state: the renderer can dump frames with png.h.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace simsols::plot {

struct Color {
  std::uint8_t r, g, b, a = 255;
  bool operator==(const Color&) const = default;
};

// Row 0 is the top row; pixel (x, y) starts at rgba[4 * (y * width + x)].
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};

struct Point {
  double x, y;
};

// Pixels [x0, x1) x [y0, y1).
struct Rect {
  int x0, y0, x1, y1;
};

// Dash pattern in pixels along the path; on <= 0 draws a solid line.
struct Dash {
  double on = 0, off = 0;
};

Image make_image(int width, int height, Color background = {255, 255, 255});
Color pixel(const Image& img, int x, int y);
void fill(Image& img, Color c);

// Blends `c` over pixel (x, y) with the given coverage in [0, 1] (multiplied
// by c.a); out-of-image pixels are ignored.
void blend_pixel(Image& img, int x, int y, Color c, double coverage);

// Anti-aliased edges on fractional coordinates.
void fill_rect(Image& img, double x0, double y0, double x1, double y1, Color c,
               std::optional<Rect> clip = {});
void fill_circle(Image& img, double cx, double cy, double r, Color c,
                 std::optional<Rect> clip = {});
void stroke_circle(Image& img, double cx, double cy, double r, double thickness, Color c,
                   std::optional<Rect> clip = {});

// Lines of the given thickness in pixels, round caps and joins.
void draw_line(Image& img, Point a, Point b, double thickness, Color c,
               std::optional<Rect> clip = {}, Dash dash = {});
void stroke_polylines(Image& img, const std::vector<std::vector<Point>>& lines, double thickness,
                      Color c, std::optional<Rect> clip = {}, Dash dash = {});

}  // namespace simsols::plot
