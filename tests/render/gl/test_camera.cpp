// The orbit camera (render/gl/camera.h): presets look the documented way,
// fit() keeps a box inside the frame and fills it, the interactive moves do
// what their names say. Pure math: no GL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/gl/camera.h"

using namespace simsols::render;

namespace {

glm::dvec2 px(const Camera& c, glm::dvec3 p, int w = 800, int h = 600) {
  return c.project(p, w, h).pixel;
}

}  // namespace

TEST(Camera, PresetsLookTheDocumentedWay) {
  Camera c;
  c.distance = 1;
  c.near_far_radius = 0.2;
  c.set_preset(ViewPreset::Front);  // x right, z up
  EXPECT_GT(px(c, {0.1, 0, 0}).x, px(c, {0, 0, 0}).x);
  EXPECT_LT(px(c, {0, 0, 0.1}).y, px(c, {0, 0, 0}).y);
  EXPECT_NEAR(px(c, {0, 0.1, 0}).x, 400, 1e-6);  // depth only
  c.set_preset(ViewPreset::Side);  // y right, z up, looking along -x
  EXPECT_GT(px(c, {0, 0.1, 0}).x, px(c, {0, 0, 0}).x);
  EXPECT_NEAR(glm::dot(c.forward(), glm::dvec3(-1, 0, 0)), 1, 1e-9);
  c.set_preset(ViewPreset::Top);  // x right, y up
  EXPECT_GT(px(c, {0.1, 0, 0}).x, px(c, {0, 0, 0}).x);
  EXPECT_LT(px(c, {0, 0.1, 0}).y, px(c, {0, 0, 0}).y);
  c.set_preset(ViewPreset::ThreeQuarter);
  EXPECT_LT(c.forward().z, 0);  // from above
  EXPECT_GT(c.forward().x, 0);
  EXPECT_EQ(parse_view_preset("three-quarter"), ViewPreset::ThreeQuarter);
  EXPECT_FALSE(parse_view_preset("iso").has_value());
}

TEST(Camera, FitKeepsTheBoxInsideAndFillsIt) {
  const glm::dvec3 lo(0, 0, 0), hi(0.06, 0.06, 0.03);
  for (bool ortho : {false, true})
    for (ViewPreset p : {ViewPreset::Front, ViewPreset::Side, ViewPreset::Top, ViewPreset::ThreeQuarter})
      for (auto [w, h] : {std::pair{800, 600}, std::pair{300, 900}, std::pair{1920, 400}}) {
        Camera c;
        c.orthographic = ortho;
        c.set_preset(p);
        c.fit(lo, hi, double(w) / h);
        double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
        for (int k = 0; k < 8; ++k) {
          const glm::dvec3 q((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
          const auto pr = c.project(q, w, h);
          EXPECT_GT(pr.depth, c.near_plane());
          EXPECT_LT(pr.depth, c.far_plane());
          x0 = std::min(x0, pr.pixel.x);
          x1 = std::max(x1, pr.pixel.x);
          y0 = std::min(y0, pr.pixel.y);
          y1 = std::max(y1, pr.pixel.y);
        }
        SCOPED_TRACE(std::string(to_string(p)) + (ortho ? " ortho " : " persp ") +
                     std::to_string(w) + "x" + std::to_string(h));
        EXPECT_GE(x0, 0);
        EXPECT_LE(x1, w);
        EXPECT_GE(y0, 0);
        EXPECT_LE(y1, h);
        // fills: the box spans most of the limiting dimension
        EXPECT_GT(std::max((x1 - x0) / w, (y1 - y0) / h), 0.6);
      }
}

TEST(Camera, InteractiveMoves) {
  Camera c;
  c.set_preset(ViewPreset::Front);
  c.fit({-1, -1, -1}, {1, 1, 1}, 4.0 / 3);
  const double d = c.distance;
  c.zoom(0.5);
  EXPECT_NEAR(c.distance, d / 2, 1e-12);
  c.orbit(0, 200);
  EXPECT_LT(c.pitch_deg, 90);  // clamped short of the pole
  c.orbit(30, -c.pitch_deg);
  EXPECT_NEAR(c.yaw_deg, 30, 1e-12);
  // panning (a drag) right by a tenth of the view height moves the scene
  // with the drag: the old target right by a tenth of the image height
  c.pitch_deg = 0;
  const glm::dvec3 t = c.target;
  c.pan(0.1, 0);
  EXPECT_NEAR(px(c, t).x, 400 + 60, 1e-6);
  c.pan(-0.1, 0.2);  // back, and up by a fifth: rows count down, so y falls by 120
  EXPECT_NEAR(px(c, t).x, 400, 1e-6);
  EXPECT_NEAR(px(c, t).y, 300 - 120, 1e-6);
  // pixels per metre at the target's depth agree with project()
  const auto a = c.project(c.target, 800, 600), b = c.project(c.target + 0.01 * c.right(), 800, 600);
  EXPECT_NEAR(b.pixel.x - a.pixel.x, 0.01 * c.pixels_per_metre(a.depth, 600), 1e-6);
}
