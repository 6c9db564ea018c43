// What a picture of a test says besides the specimen: a caption in the top
// left corner (the test's title, then its state: the apparatus' own
// quantities, the step and the simulated time) and a scale bar in the
// bottom left corner.
//
// The scale bar is measured at the camera's target (the specimen's centre
// once the camera is fitted): a 1-2-5 length near a sixth of the frame's
// width there, drawn with its length in mm. Under perspective, parts of the
// specimen nearer the camera look larger than the bar says, farther ones
// smaller; the bar's label says where it holds ("at the centre").
//
// Text and bar are light on a translucent dark panel, sized with the image
// (1 at 900 px tall), like the colour legend (render/plot/colormap.h).
#pragma once

#include <string>

#include "render/gl/camera.h"
#include "render/plot/image.h"

namespace simsols::render {

struct FrameCaption {
  std::string title;  // "Direct shear, 6.35 mm glass beads, σ = 160 kPa"
  std::string state;  // "δ = 2.62 mm, τ/σ = 0.157, σ = 160.0 kPa · step 190517 · t = 0.1526 s"
};

// Draws the caption's non-empty lines; returns the rectangle covered.
plot::Rect draw_caption(plot::Image& img, const FrameCaption& caption);

// The bar's length (m): 1, 2 or 5 times a power of ten, the largest not
// longer than `most` (> 0).
double scale_bar_length(double most);

// Draws the scale bar for `camera` (the picture's camera, aspect from the
// image); returns the rectangle covered (empty when the camera's scale at
// its target cannot be measured).
plot::Rect draw_scale_bar(plot::Image& img, const Camera& camera);

}  // namespace simsols::render
