// What the renderer draws of a running simulation (render/view/sim_view.h):
// the force chains of a loaded column show the column's contacts and
// nothing else; the caption's scale bar.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/gl/gl_context.h"
#include "render/gl/renderer.h"
#include "render/view/frame_caption.h"
#include "render/view/sim_view.h"
#include "solver/core/engine_options.h"
#include "solver/core/simulation.h"
#include "tests/support/test_support.h"

using namespace simsols;
using namespace simsols::render;
using simsols::testing::empty_scene;
using simsols::testing::glass;
using simsols::testing::plane;
using simsols::testing::sphere;

namespace {

constexpr double kR = 1e-3, kSqueeze = 2e-4;  // bead radius (m); overlap per radius
constexpr int kColumn = 5;

// A column of five beads squeezed between a floor and a ceiling (no gravity:
// every contact loaded by the squeeze), and beside it two beads 0.05 R from
// the column: neighbours in its lists, touching nothing.
Scene loaded_column() {
  Scene s = empty_scene(Precision::Float, glass());
  for (int k = 0; k < kColumn; ++k)
    s.particles.push_back(sphere(kR, {0, 0, (2 * k + 1) * kR * (1 - kSqueeze)}));
  for (double side : {-1.0, 1.0})
    s.particles.push_back(sphere(kR, {side * 2.05 * kR, 0, 5 * kR}));
  s.walls.push_back(plane("floor", {0, 0, 0}, {0, 0, 1}));
  s.walls.push_back(plane("ceiling", {0, 0, 2 * kColumn * kR * (1 - kSqueeze)}, {0, 0, -1}));
  s.numerics.duration = 1;
  return s;
}

bool lit(const plot::Image& img, int x, int y) {
  const plot::Color c = plot::pixel(img, x, y);
  return c.r + c.g + c.b > 0;
}

}  // namespace

TEST(SimulationView, ChainsOfALoadedColumnShowItsContactsAndNothingElse) {
  auto ctx = create_headless_context();
  const Gl& gl = ctx->gl();
  auto device = Device::open(engine_options_from_environment(), cl_share_properties(ctx->share_handles()));
  Simulation sim(device, loaded_column());
  sim.advance(20);
  SimulationView view(gl, sim);
  const auto update = view.update(ColorField::Layer, true);
  EXPECT_EQ(update.contacts.total, size_t(kColumn - 1 + 2)) << "4 pairs and 2 wall contacts";

  const int W = 300, H = 400;
  Renderer r(gl);
  r.resize(W, H);
  Camera cam;
  cam.set_preset(ViewPreset::Front);  // x to the right, z up
  cam.fit(view.lo(), view.hi(), double(W) / H);
  ViewSettings s;
  s.mode = ViewMode::Chains;
  s.show_beads = false;
  s.show_walls = false;
  s.chain_threshold = 0;  // every touching contact
  s.background = {0, 0, 0};
  const FrameGeometry g = view.geometry();
  r.draw(cam, g, s);
  const plot::Image img = r.read_pixels();

  // in the render frame (relative to the view's origin)
  auto px = [&](double x, double z) {
    const glm::dvec3 o = glm::dvec3(view.packer().origin()[0], view.packer().origin()[1],
                                    view.packer().origin()[2]);
    return cam.project(glm::dvec3(x, 0, z) - o, W, H).pixel;
  };
  const auto bottom = px(0, 0), top = px(0, 2 * kColumn * kR);
  const double tube = std::abs(px(0.45 * kR, 5 * kR).x - px(0, 5 * kR).x);  // at F_max
  ASSERT_GT(tube, 3) << "the tube should be several pixels wide";
  // nothing outside the column's tube
  int outside = 0, inside = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!lit(img, x, y)) continue;
      const bool in_column = std::abs(x + 0.5 - bottom.x) <= tube + 1.5 && y + 0.5 >= top.y - tube - 1.5 &&
                             y + 0.5 <= bottom.y + tube + 1.5;
      (in_column ? inside : outside)++;
    }
  EXPECT_EQ(outside, 0) << "pixels drawn away from the column";
  // the column's axis covered from the floor to the ceiling, without a gap
  const int x = int(bottom.x);
  int gaps = 0;
  for (int y = int(top.y) + 1; y < int(bottom.y); ++y) gaps += !lit(img, x, y);
  EXPECT_EQ(gaps, 0);
  EXPECT_GT(inside, int(0.8 * 2 * tube * (bottom.y - top.y)) / 2);
  // bead pairs in the force colours (warm), the wall contacts in theirs
  for (int k = 1; k < kColumn; ++k) {
    const auto m = px(0, 2 * k * kR);
    const plot::Color c = plot::pixel(img, int(m.x), int(m.y));
    EXPECT_GT(int(c.r), int(c.b) + 40) << "pair " << k;
  }
  for (double z : {0.5 * kR, (2 * kColumn - 0.5) * kR}) {
    const auto m = px(0, z);
    const plot::Color c = plot::pixel(img, int(m.x), int(m.y));
    EXPECT_NEAR(c.b, 255 * s.wall_chain_color.b, 4) << "wall contact at z = " << z;
    EXPECT_NEAR(c.r, 255 * s.wall_chain_color.r, 4) << "wall contact at z = " << z;
  }
}

// The scale bar is 1, 2 or 5 times a power of ten, the largest that fits.
TEST(FrameCaption, ScaleBarLengthsAreOneTwoFive) {
  EXPECT_DOUBLE_EQ(scale_bar_length(0.037), 0.02);
  EXPECT_DOUBLE_EQ(scale_bar_length(0.01), 0.01);
  EXPECT_DOUBLE_EQ(scale_bar_length(0.0099), 0.005);
  EXPECT_DOUBLE_EQ(scale_bar_length(0.0021), 0.002);
  EXPECT_DOUBLE_EQ(scale_bar_length(7.0), 5.0);
}

// The bar is as long as the length it names, measured at the camera's
// target: 10 mm of the world at the target span the bar's pixels.
TEST(FrameCaption, ScaleBarSpansItsLengthAtTheTarget) {
  plot::Image img = plot::make_image(900, 600, {0, 0, 0});
  Camera cam;
  cam.set_preset(ViewPreset::Front);
  cam.target = {0, 0, 0};
  cam.distance = 0.2;
  const plot::Rect r = draw_scale_bar(img, cam);
  ASSERT_GT(r.x1, r.x0);
  const double per_m = std::abs(cam.project({1e-3, 0, 0}, 900, 600).pixel.x -
                                cam.project({0, 0, 0}, 900, 600).pixel.x) / 1e-3;
  const double length = scale_bar_length(900 / 6.0 / per_m);
  // the bar: the longest run of light pixels on a row of the panel
  int longest = 0;
  for (int y = r.y0; y < r.y1; ++y) {
    int run = 0;
    for (int x = r.x0; x < r.x1; ++x) {
      run = plot::pixel(img, x, y).r > 200 ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  EXPECT_NEAR(longest, length * per_m, 2.0);
}
