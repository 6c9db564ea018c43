// Eight-view Alioscopy output (render/gl/alioscopy.h, render/gl/stereo_rig.h):
// the interleaving is checked subpixel by subpixel against the formula
// written out here, independently of the library; de-interleaving gives the
// views back; the rig puts the focus plane at screen depth and shifts points
// in front of it by the disparity its geometry predicts.
#include <unistd.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "render/gl/alioscopy.h"
#include "render/gl/gl_context.h"
#include "render/gl/renderer.h"
#include "render/gl/stereo_rig.h"

using namespace simsols::render;
namespace plot = simsols::plot;

namespace {

GlContext& context() {
  static std::unique_ptr<GlContext> ctx = create_headless_context();
  return *ctx;
}

// Distinct value per view and channel.
int level(int v, int c) { return 5 + 29 * v + 9 * c; }

// The formula, written independently of the library.
int expected_view(int X, int Y, int c, int phase, bool reversed, bool flip) {
  int s = (flip ? -Y : Y) - (3 * X + c) + phase;
  int v = ((s % 8) + 8) % 8;
  return reversed ? 7 - v : v;
}

// An image of random bytes (alpha too), from a linear congruential
// sequence that `seed` carries on between calls.
plot::Image random_image(int width, int height, std::uint32_t& seed) {
  plot::Image img = plot::make_image(width, height);
  for (auto& b : img.rgba) {
    seed = seed * 1664525u + 1013904223u;
    b = std::uint8_t(seed >> 24);
  }
  return img;
}

}  // namespace

TEST(Alioscopy, InterleavingMatchesTheFormulaAtEverySubpixel) {
  DisplayProfile p;  // 1920 x 1080
  AlioscopyOutput out(context().gl(), p);
  struct Case {
    glm::ivec2 window;
    int phase;
    bool reversed, flip;
  };
  for (const Case& k : {Case{{0, 0}, 0, false, false}, Case{{37, 11}, 0, false, false},
                        Case{{5, 1000}, 3, false, false}, Case{{0, 0}, 0, true, false},
                        Case{{0, 0}, 0, false, true}, Case{{123, 77}, 6, true, true}}) {
    DisplayProfile q = p;
    q.phase = k.phase;
    q.reversed = k.reversed;
    q.flip_slant = k.flip;
    AlioscopyOutput o(context().gl(), q);
    for (int v = 0; v < 8; ++v)
      o.fill_view(v, {level(v, 0) / 255.f, level(v, 1) / 255.f, level(v, 2) / 255.f, 1});
    o.compose(AlioscopyOutput::Mode::Interleaved, 0, k.window);
    const plot::Image img = o.read_pixels();
    ASSERT_EQ(img.width, 1920);
    ASSERT_EQ(img.height, 1080);
    long wrong = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const int v = expected_view(k.window.x + x, k.window.y + y, c, k.phase, k.reversed, k.flip);
          wrong += img.rgba[(std::size_t(y) * img.width + x) * 4 + c] != level(v, c);
        }
    EXPECT_EQ(wrong, 0) << "window " << k.window.x << "," << k.window.y << " phase " << k.phase
                        << " reversed " << k.reversed << " flip " << k.flip;
  }
}

TEST(Alioscopy, DeinterleavingGivesEachViewBack) {
  DisplayProfile p;
  p.width = 200;
  p.height = 120;
  p.view_scale = 1;
  p.nearest_views = true;
  p.phase = 5;
  AlioscopyOutput out(context().gl(), p);
  std::vector<plot::Image> views;
  std::uint32_t seed = 12345;
  for (int v = 0; v < 8; ++v) {
    plot::Image img = random_image(p.view_width(), p.view_height(), seed);
    for (std::size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
    out.upload_view(v, img);
    views.push_back(img);
  }
  const glm::ivec2 window{13, 7};
  out.compose(AlioscopyOutput::Mode::Interleaved, 0, window);
  const plot::Image inter = out.read_pixels();
  for (int k = 0; k < 8; ++k) {
    const plot::Image lens = deinterleave(inter, k, p, window);
    long shown = 0, wrong = 0, wrong_subsampled = 0;
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const std::size_t i = (std::size_t(y) * p.width + x) * 4 + c;
          if (expected_view(window.x + x, window.y + y, c, p.phase, false, false) == k) {
            ++shown;
            wrong += lens.rgba[i] != views[k].rgba[i];
          } else {
            // elsewhere: the view's value at the nearest shown column
            bool found = false;
            for (int d = 0; d <= 4 && !found; ++d)
              for (int sx : {x - d, x + d})
                if (!found && sx >= 0 && sx < p.width &&
                    expected_view(window.x + sx, window.y + y, c, p.phase, false, false) == k) {
                  found = true;
                  wrong_subsampled +=
                      lens.rgba[i] != views[k].rgba[(std::size_t(y) * p.width + sx) * 4 + c];
                }
          }
        }
    EXPECT_EQ(shown, long(p.width) * p.height * 3 / 8) << "one subpixel in 8 per view";
    EXPECT_EQ(wrong, 0) << "view " << k;
    EXPECT_EQ(wrong_subsampled, 0) << "view " << k;
  }
}

// compose_into (the lab's window, no copy) writes at its offset exactly what
// compose writes into the output's own target, with the views at their
// default size (3/8 of the output) sampled at the nearest texel.
TEST(Alioscopy, ComposedIntoAnotherFramebufferAsIntoItsOwn) {
  DisplayProfile p;
  p.width = 200;
  p.height = 120;
  p.phase = 3;
  AlioscopyOutput out(context().gl(), p);
  EXPECT_EQ(out.view_width(), 75);
  EXPECT_EQ(out.view_height(), 45);
  std::uint32_t seed = 777;
  for (int v = 0; v < 8; ++v) {
    out.upload_view(v, random_image(out.view_width(), out.view_height(), seed));
  }
  const glm::ivec2 window{5, 9};
  out.compose(AlioscopyOutput::Mode::Interleaved, 0, window);
  const plot::Image own = out.read_pixels();
  AlioscopyOutput big(context().gl(), p);
  big.resize_output(260, 170);
  const glm::ivec2 at{40, 30};  // GL: from the bottom left
  out.compose_into(big.framebuffer(), at, AlioscopyOutput::Mode::Interleaved, 0, window);
  const plot::Image there = big.read_pixels();
  const int top = 170 - at.y - p.height;  // the same rectangle, rows from the top
  long differ = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      for (int c = 0; c < 3; ++c)
        differ += own.rgba[(std::size_t(y) * p.width + x) * 4 + c] !=
                  there.rgba[(std::size_t(y + top) * 260 + x + at.x) * 4 + c];
  EXPECT_EQ(differ, 0);
}

TEST(Alioscopy, GridAndSingleViewShowTheViews) {
  DisplayProfile p;
  p.width = 400;
  p.height = 200;
  AlioscopyOutput out(context().gl(), p);
  for (int v = 0; v < 8; ++v)
    out.fill_view(v, {level(v, 0) / 255.f, level(v, 1) / 255.f, level(v, 2) / 255.f, 1});
  out.compose(AlioscopyOutput::Mode::Grid);
  plot::Image g = out.read_pixels();
  const GridLayout grid = out.grid();
  EXPECT_EQ(grid.columns, 3);  // 2:1 views in 3 x 3 cells of 2:1: none letterboxed
  EXPECT_EQ(grid.rows, 3);
  for (int v = 0; v < 8; ++v) {
    const plot::Rect c = grid.cell(v, 400, 200, 2.0);
    for (auto [x, y] : {std::pair{c.x0 + 1, c.y0 + 1}, std::pair{(c.x0 + c.x1) / 2, (c.y0 + c.y1) / 2},
                        std::pair{c.x1 - 2, c.y1 - 2}}) {  // view 0 top left, its whole cell
      const plot::Color px = plot::pixel(g, x, y);
      EXPECT_EQ(px.r, level(v, 0)) << v;
      EXPECT_EQ(px.b, level(v, 2)) << v;
    }
  }
  const plot::Color ninth = plot::pixel(g, 350, 180);  // the empty ninth cell
  EXPECT_EQ(ninth.r + ninth.g + ninth.b, 0);
  out.compose(AlioscopyOutput::Mode::Single, 6);
  g = out.read_pixels();
  EXPECT_EQ(plot::pixel(g, 7, 190).g, level(6, 1));
}

// The grid shows each view largest: 3 x 3 for views of the output's own
// aspect (cells of that aspect, nothing letterboxed); cells lie inside the
// output without overlapping, in reading order.
TEST(Alioscopy, GridLayoutShowsTheViewsLargest) {
  for (auto [w, h] : {std::pair{1920, 1080}, std::pair{1400, 860}, std::pair{400, 200}}) {
    const double aspect = double(w) / h;
    const GridLayout g = grid_layout(w, h, aspect);
    EXPECT_EQ(g.columns * g.rows, 9) << w << "x" << h;
    double area = 0;
    for (int k = 0; k < 8; ++k) {
      const plot::Rect c = g.cell(k, w, h, aspect);
      EXPECT_GE(c.x0, 0);
      EXPECT_GE(c.y0, 0);
      EXPECT_LE(c.x1, w);
      EXPECT_LE(c.y1, h);
      EXPECT_NEAR(double(c.x1 - c.x0) / (c.y1 - c.y0), aspect, 2.0 * aspect / (c.y1 - c.y0));  // 1 px
      area += double(c.x1 - c.x0) * (c.y1 - c.y0);
      if (k > 0) {
        const plot::Rect p = g.cell(k - 1, w, h, aspect);
        EXPECT_TRUE(c.y0 > p.y0 || c.x0 >= p.x1) << "view " << k << " after view " << k - 1;
      }
    }
    EXPECT_NEAR(area / (double(w) * h), 8.0 / 9.0, 0.02);  // a 4 x 2 grid showed 8/16
  }
  // square views on a 16:9 output: 4 x 2 cells of 480 x 540 hold 480 px
  // squares, 3 x 3 cells of 640 x 360 only 360 px ones
  const GridLayout square = grid_layout(1920, 1080, 1.0);
  EXPECT_EQ(square.columns, 4);
  EXPECT_EQ(square.rows, 2);
  const plot::Rect c = square.cell(5, 1920, 1080, 1.0);
  EXPECT_EQ(c.x1 - c.x0, 480);
  EXPECT_EQ(c.y0, 540 + 30);  // second row, centred in its 540 px
}

TEST(Alioscopy, ProfileErrorsNameFileFieldAndRange) {
  const auto dir = std::filesystem::temp_directory_path() / ("simsols_alioscopy_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto write = [&](const char* name, const char* text) {
    const auto p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  };
  const DisplayProfile ok = load_display_profile(
      write("ok.toml", "[display]\nwidth = 3840\nheight = 2160\nphase = 2\nreversed = true\n"
                       "[rig]\nview_scale = 0.25\n"));
  EXPECT_EQ(ok.width, 3840);
  EXPECT_EQ(ok.view_width(), 960);
  EXPECT_EQ(ok.view_size(1000, 500), glm::ivec2(250, 125));  // views follow the output
  EXPECT_TRUE(ok.reversed);
  const std::pair<const char*, const char*> bad[] = {
      {"[display]\nphase = 8\n", "display.phase"},
      {"[display]\nviews = 9\n", "display.views"},
      {"[display]\nwidth = 0\n", "display.width"},
      {"[display]\nreversed = 1\n", "display.reversed"},
      {"[rig]\nview_scale = 0\n", "rig.view_scale"},
      {"[rig]\nfocus = -1\n", "rig.focus"},
      {"[display]\nslant = 1\n", "display.slant"},
  };
  for (auto [text, field] : bad) {
    const std::string file = write("bad.toml", text);
    try {
      load_display_profile(file);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::runtime_error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("bad.toml"), std::string::npos) << m;
      EXPECT_NE(m.find(field), std::string::npos) << m;
    }
  }
  EXPECT_THROW(load_display_profile((dir / "missing.toml").string()), std::runtime_error);
  // the shipped profile loads, and equals the built-in defaults
  const DisplayProfile hd = load_display_profile(SIMSOLS_ASSETS_DIR "/displays/alioscopy_hd.toml");
  const DisplayProfile def;
  EXPECT_EQ(hd.name, def.name);
  EXPECT_EQ(hd.width, def.width);
  EXPECT_EQ(hd.height, def.height);
  EXPECT_EQ(hd.phase, def.phase);
  EXPECT_EQ(hd.reversed, def.reversed);
  EXPECT_EQ(hd.flip_slant, def.flip_slant);
  EXPECT_EQ(hd.view_scale, def.view_scale);
  EXPECT_EQ(hd.interaxial_ratio, def.interaxial_ratio);
  EXPECT_EQ(hd.interaxial, def.interaxial);
  EXPECT_EQ(hd.focus, def.focus);
}

// The rig: a point on the focus plane lands on the same pixel in all views;
// a point in front moves left from view 0 to 7, behind it right, by the
// predicted disparity.
TEST(StereoRig, FocusPlaneAtScreenDepthAndPredictedDisparity) {
  Camera cam;
  cam.set_preset(ViewPreset::ThreeQuarter);
  cam.fit({-0.03, -0.03, 0}, {0.03, 0.03, 0.03}, 16.0 / 9);
  StereoRig rig;
  const int W = 960, H = 540;
  const double aspect = double(W) / H, F = rig.focus_for(cam);
  EXPECT_NEAR(rig.interaxial_for(cam), F * 6.5 / 400, 1e-15);
  auto pixel = [&](int k, const glm::dvec3& p) {
    const ViewProjection vp = rig.view(cam, k, aspect);
    const glm::dvec4 c = vp.projection * vp.view * glm::dvec4(p, 1);
    return glm::dvec2((c.x / c.w * 0.5 + 0.5) * W, (0.5 - c.y / c.w * 0.5) * H);
  };
  const glm::dvec3 on_plane = cam.target + 0.01 * cam.right() + 0.004 * cam.up();
  for (int k = 1; k < 8; ++k) {
    EXPECT_NEAR(pixel(k, on_plane).x, pixel(0, on_plane).x, 1e-6);
    EXPECT_NEAR(pixel(k, on_plane).y, pixel(0, on_plane).y, 1e-6);
  }
  // the central pair straddles the user's camera: same picture on average
  const glm::dvec2 user = cam.project(on_plane, W, H).pixel;
  EXPECT_NEAR(pixel(0, on_plane).x, user.x, 1e-6);
  for (double z : {0.8 * F, 1.3 * F}) {
    const glm::dvec3 p = cam.eye() + z * cam.forward() + 0.005 * cam.right();
    for (int k = 1; k < 8; ++k) {
      const double d = pixel(k, p).x - pixel(0, p).x;
      EXPECT_NEAR(d, rig.disparity_px(cam, k, z, aspect, W), 1e-6);
      if (z < F) EXPECT_LT(pixel(k, p).x, pixel(k - 1, p).x);
      else EXPECT_GT(pixel(k, p).x, pixel(k - 1, p).x);
      EXPECT_NEAR(pixel(k, p).y, pixel(0, p).y, 1e-6);  // no vertical parallax
    }
  }
}

// End to end: a bead in front of the focus plane, drawn into the eight
// views, moves by the predicted disparity (disc centroids, within 0.5 px).
TEST(StereoRig, RenderedBeadShiftsByThePredictedDisparity) {
  const Gl& gl = context().gl();
  DisplayProfile p;
  p.width = 640;
  p.height = 360;
  p.view_scale = 1;
  AlioscopyOutput out(gl, p);
  Renderer r(gl);
  GeometryBuffers buf(gl);
  Camera cam;
  cam.set_preset(ViewPreset::Front);
  cam.target = {0, 0, 0};
  cam.distance = 0.3;
  cam.near_far_radius = 0.1;
  StereoRig rig;
  rig.interaxial = 0.01;  // exaggerated, for pixels to measure
  const double z = 0.24;  // view depth of the bead, in front of F = 0.3
  const glm::vec3 c = glm::vec3(cam.eye() + z * cam.forward());
  buf.upload_beads({c.x, c.y, c.z, 0.006f}, {0.f});
  buf.mutable_geometry().lo = {-0.05, -0.1, -0.05};
  buf.mutable_geometry().hi = {0.05, 0.1, 0.05};
  ViewSettings s;
  s.lighting = false;
  s.show_walls = false;
  s.bead_map = plot::ColorMap::Categorical;
  s.background = {0, 0, 0};
  out.render_views(r, rig, cam, buf.geometry(), s);
  double x0 = 0;
  for (int k = 0; k < 8; ++k) {
    const plot::Image v = out.read_view(k);
    double sx = 0, n = 0;
    for (int y = 0; y < v.height; ++y)
      for (int x = 0; x < v.width; ++x)
        if (plot::pixel(v, x, y).r > 0 || plot::pixel(v, x, y).g > 0) {
          sx += x + 0.5;
          n += 1;
        }
    ASSERT_GT(n, 100) << "view " << k;
    if (k == 0) x0 = sx / n;
    else
      EXPECT_NEAR(sx / n - x0, rig.disparity_px(cam, k, z, double(p.width) / p.height, v.width), 0.5)
          << "view " << k;
  }
}
