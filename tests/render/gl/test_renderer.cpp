// The renderer, headless: geometry of the impostors, depth, transparency,
// force chains, golden images and GL state. Every expected value comes from
// the camera model or a CPU ray cast, not from a previous run (except the
// golden images, which guard against regressions).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <glm/glm.hpp>

#include "render/gl/camera.h"
#include "render/plot/colormap.h"
#include "render/gl/gl_context.h"
#include "render/plot/png.h"
#include "render/gl/renderer.h"

using namespace simsols::render;
namespace plot = simsols::plot;

namespace {

GlContext& context() {
  static std::unique_ptr<GlContext> ctx = [] {
    auto c = create_headless_context();
    std::printf("GL context: %s\n", c->description().c_str());
    return c;
  }();
  return *ctx;
}

// A camera on the -y side looking along +y at the origin from distance d.
Camera axis_camera(double d, double fov = 30) {
  Camera c;
  c.set_preset(ViewPreset::Front);
  c.target = {0, 0, 0};
  c.distance = d;
  c.fov_y_deg = fov;
  c.near_far_radius = d / 2;
  return c;
}

ViewSettings flat_settings() {
  ViewSettings s;
  s.lighting = false;
  s.show_walls = false;
  s.bead_map = plot::ColorMap::Categorical;
  s.background = {0, 0, 0};
  return s;
}

struct Bead {
  glm::vec3 c;
  float r;
  float value;
};

void upload(GeometryBuffers& b, const std::vector<Bead>& beads) {
  std::vector<float> xyzr, values;
  for (const Bead& x : beads) {
    xyzr.insert(xyzr.end(), {x.c.x, x.c.y, x.c.z, x.r});
    values.push_back(x.value);
  }
  b.upload_beads(xyzr, values);
  glm::dvec3 lo(1e30), hi(-1e30);
  for (const Bead& x : beads) {
    lo = glm::min(lo, glm::dvec3(x.c) - double(x.r));
    hi = glm::max(hi, glm::dvec3(x.c) + double(x.r));
  }
  b.mutable_geometry().lo = lo;
  b.mutable_geometry().hi = hi;
}

bool is_background(const plot::Image& img, int x, int y, plot::Color bg = {0, 0, 0}) {
  const plot::Color p = plot::pixel(img, x, y);
  return p.r == bg.r && p.g == bg.g && p.b == bg.b;
}

// The ray through the centre of pixel (x, y), in world coordinates.
struct Ray {
  glm::dvec3 o, d;
};
Ray pixel_ray(const Camera& cam, int x, int y, int w, int h) {
  const double t = std::tan(cam.fov_y_deg * 3.14159265358979323846 / 360);
  const double ndc_x = (x + 0.5) / w * 2 - 1, ndc_y = 1 - (y + 0.5) / h * 2;
  const glm::dvec3 dir = cam.forward() + ndc_x * t * double(w) / h * cam.right() + ndc_y * t * cam.up();
  return {cam.eye(), glm::normalize(dir)};
}

// Distance along the ray to the sphere, or -1.
double hit(const Ray& ray, const Bead& b) {
  const glm::dvec3 oc = glm::dvec3(b.c) - ray.o;
  const double t = glm::dot(oc, ray.d);
  const glm::dvec3 perp = oc - t * ray.d;
  const double h2 = double(b.r) * b.r - glm::dot(perp, perp);
  return h2 < 0 ? -1 : t - std::sqrt(h2);
}

plot::Color category(int k) { return plot::colormap_color(plot::ColorMap::Categorical, k); }

}  // namespace

TEST(Renderer, ContextIsCore33AndNamed) {
  GlContext& c = context();
  EXPECT_FALSE(c.description().empty());
  GLint major = 0, minor = 0;
  c.gl().GetIntegerv(GL_MAJOR_VERSION, &major);
  c.gl().GetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33);
}

// The disc of a bead on the view axis covers pi R^2 pixels, R = f r /
// sqrt(d^2 - r^2) with f = (H/2) / tan(fov/2): the cone of rays tangent to
// the sphere. Off the axis the outline is an ellipse; the count is compared
// with a CPU ray cast through every pixel centre.
TEST(Renderer, BeadDiscAreaMatchesProjection) {
  const Gl& gl = context().gl();
  Renderer r(gl);
  const int W = 480, H = 400;
  r.resize(W, H);
  GeometryBuffers buf(gl);
  const double d = 0.5, radius = 0.02;
  const Camera cam = axis_camera(d);
  for (int pass = 0; pass < 2; ++pass) {
    // pass 0: on the axis; pass 1: off the axis (up and to the right)
    const Bead b{pass == 0 ? glm::vec3(0) : glm::vec3(0.07f, 0.f, 0.05f), float(radius), 0};
    upload(buf, {b});
    r.draw(cam, buf.geometry(), flat_settings());
    const plot::Image img = r.read_pixels();
    long count = 0, ray_count = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        count += !is_background(img, x, y);
        ray_count += hit(pixel_ray(cam, x, y, W, H), b) > 0;
      }
    if (pass == 0) {
      const double f = H / 2.0 / std::tan(15 * 3.14159265358979323846 / 180);
      const double R = f * radius / std::sqrt(d * d - radius * radius);
      const double area = 3.14159265358979323846 * R * R;
      EXPECT_NEAR(count / area, 1.0, 0.01) << "pixels " << count << ", projection " << area;
    }
    EXPECT_NEAR(double(count) / ray_count, 1.0, 0.01) << "pass " << pass;
    EXPECT_GT(ray_count, 1000);
  }
}

// Two intersecting beads: each pixel shows the bead whose surface the ray
// meets first, whatever the drawing order (per-pixel depth from the hit).
TEST(Renderer, IntersectingBeadsOccludeByDepth) {
  const Gl& gl = context().gl();
  Renderer r(gl);
  const int W = 320, H = 240;
  r.resize(W, H);
  GeometryBuffers buf(gl);
  const Camera cam = axis_camera(0.4);
  // A is nearer the camera by its centre but smaller: B's surface wins over
  // part of the overlap, A's over the rest.
  const Bead a{{0.f, -0.005f, 0.f}, 0.01f, 0}, b{{0.012f, 0.f, 0.002f}, 0.02f, 1};
  int order = 0;
  for (const auto& beads : {std::vector<Bead>{a, b}, std::vector<Bead>{b, a}}) {
    upload(buf, beads);
    r.draw(cam, buf.geometry(), flat_settings());
    const plot::Image img = r.read_pixels();
    long checked = 0, wrong = 0, a_wins = 0, b_wins = 0;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const Ray ray = pixel_ray(cam, x, y, W, H);
        const double ta = hit(ray, a), tb = hit(ray, b);
        if (ta < 0 || tb < 0) continue;  // only where both are hit
        if (std::abs(ta - tb) < 2e-5) continue;  // the intersection curve itself
        const int expect = ta < tb ? 0 : 1;
        (expect == 0 ? a_wins : b_wins)++;
        ++checked;
        wrong += !(plot::pixel(img, x, y) == category(expect));
      }
    EXPECT_GT(a_wins, 80) << "order " << order;
    EXPECT_GT(b_wins, 200) << "order " << order;
    EXPECT_LT(double(wrong) / checked, 0.002) << wrong << " of " << checked << ", order " << order;
    ++order;
  }
}

// A section normal to y keeps the beads whose centres lie within half its
// width (in mean bead diameters) of the middle of what is drawn: of three
// beads at y = -3r, 0, +3r, a slab 1 diameter wide keeps the middle one,
// with the same pixels as drawn alone; one 7 diameters wide keeps all.
TEST(Renderer, ASectionDrawsOnlyTheBeadsInItsSlab) {
  const Gl& gl = context().gl();
  Renderer r(gl);
  const int W = 320, H = 240;
  r.resize(W, H);
  GeometryBuffers buf(gl);
  const Camera cam = axis_camera(0.5);
  const float radius = 0.01f;
  const std::vector<Bead> beads{{{-0.05f, -0.03f, 0.f}, radius, 0},
                                {{0.f, 0.f, 0.f}, radius, 1},
                                {{0.05f, 0.03f, 0.f}, radius, 2}};
  auto counts = [&](const std::vector<Bead>& drawn, ViewSettings s) {
    upload(buf, drawn);
    buf.mutable_geometry().lo = {-0.06, -0.04, -0.01};  // the three beads' bounds either way
    buf.mutable_geometry().hi = {0.06, 0.04, 0.01};
    r.draw(cam, buf.geometry(), s);
    const plot::Image img = r.read_pixels();
    std::array<long, 3> n{};
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        for (int k = 0; k < 3; ++k) n[k] += plot::pixel(img, x, y) == category(k);
    return n;
  };
  ViewSettings slab = flat_settings();
  ASSERT_EQ(parse_section("y:1", slab.section), "");
  EXPECT_EQ(slab.section.axis, 1);
  const auto cut = counts(beads, slab);
  const auto alone = counts({beads[1]}, flat_settings());
  EXPECT_EQ(cut[0], 0);
  EXPECT_EQ(cut[2], 0);
  EXPECT_GT(alone[1], 150);  // a disc of about 9 px radius
  EXPECT_EQ(cut[1], alone[1]);
  ASSERT_EQ(parse_section("y:7", slab.section), "");
  const auto wide = counts(beads, slab);
  for (int k = 0; k < 3; ++k) EXPECT_GT(wide[k], 150) << k;
  ASSERT_EQ(parse_section("off", slab.section), "");
  EXPECT_EQ(counts(beads, slab), wide);
}

// "AXIS[:WIDTH]" or "off"; anything else is refused, naming what is allowed,
// and leaves the settings as they were.
TEST(Renderer, SectionTextIsReadOrRefused) {
  Section s;
  EXPECT_EQ(section_text(s), "off");
  ASSERT_EQ(parse_section("z", s), "");
  EXPECT_EQ(s.axis, 2);
  EXPECT_FLOAT_EQ(s.width, 2.0f);  // the default width
  ASSERT_EQ(parse_section("x:1.5", s), "");
  EXPECT_EQ(section_text(s), "x:1.5");
  for (const char* bad : {"w", "xy", "x:", "x:0", "x:-1", "x:2mm", "x:1e9", ""}) {
    Section t = s;
    const std::string problem = parse_section(bad, t);
    EXPECT_NE(problem, "") << bad;
    EXPECT_EQ(section_text(t), "x:1.5") << bad;
  }
  EXPECT_NE(parse_section("w", s).find("x, y, z"), std::string::npos);
  EXPECT_NE(parse_section("x:0", s).find("(0, 1000]"), std::string::npos);
}

// Qualitative map (grains): the shader's hash (shaders/common.glsl) picks
// the entry plot::qualitative_index picks, for small and large identities
// (exact in float up to 2^24).
TEST(Renderer, QualitativeColoursMatchTheHostHash) {
  const Gl& gl = context().gl();
  Renderer r(gl);
  const int W = 640, H = 160;
  r.resize(W, H);
  GeometryBuffers buf(gl);
  const Camera cam = axis_camera(0.5);
  const float ids[] = {0, 1, 2, 3, 4, 5, 6, 7, 10, 11, 1000, 123457, 16777215};
  const int n = int(std::size(ids));
  std::vector<Bead> beads;
  for (int k = 0; k < n; ++k)
    beads.push_back({{float(-0.18 + 0.36 * k / (n - 1)), 0.f, 0.f}, 0.01f, ids[k]});
  upload(buf, beads);
  ViewSettings s = flat_settings();
  s.bead_map = plot::ColorMap::Qualitative;
  r.draw(cam, buf.geometry(), s);
  const plot::Image img = r.read_pixels();
  const ViewProjection v = ViewProjection::of(cam, double(W) / H);
  const glm::dmat4 vp = v.projection * v.view;
  for (int k = 0; k < n; ++k) {
    const glm::dvec4 c = vp * glm::dvec4(glm::dvec3(beads[k].c), 1.0);
    const int x = int((c.x / c.w * 0.5 + 0.5) * W), y = int((0.5 - c.y / c.w * 0.5) * H);
    EXPECT_EQ(plot::pixel(img, x, y), plot::colormap_color(plot::ColorMap::Qualitative, ids[k]))
        << "grain " << ids[k];
  }
}

// Weighted blended transparency: one bead gives C a + bg (1 - a); two give
// the documented formula with the depth weights at the pixel.
TEST(Renderer, TransparencyBlendsTheDocumentedColours) {
  const Gl& gl = context().gl();
  Renderer r(gl);
  const int W = 200, H = 200;
  r.resize(W, H);
  GeometryBuffers buf(gl);
  const Camera cam = axis_camera(0.4);
  ViewSettings s = flat_settings();
  s.mode = ViewMode::Transparent;
  s.bead_alpha = 0.4f;
  s.background = {40, 60, 80};
  const Bead a{{-0.006f, -0.01f, 0.f}, 0.015f, 2}, b{{0.006f, 0.012f, 0.f}, 0.015f, 5};
  upload(buf, {a, b});
  r.draw(cam, buf.geometry(), s);
  const plot::Image img = r.read_pixels();
  // the scene's depth range, as the renderer takes it (bounds of the geometry)
  double dmin = 1e30, dmax = -1e30;
  const FrameGeometry g = buf.geometry();
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c((k & 1) ? g.hi.x : g.lo.x, (k & 2) ? g.hi.y : g.lo.y, (k & 4) ? g.hi.z : g.lo.z);
    const double dd = -(cam.view() * glm::dvec4(c, 1)).z;
    dmin = std::min(dmin, dd);
    dmax = std::max(dmax, dd);
  }
  const double alpha = s.bead_alpha;
  auto weight = [&](double depth) {
    const double k = 1 - std::clamp((depth - dmin) / (dmax - dmin), 0.0, 1.0);
    return alpha * std::max(0.01, 100 * k * k * k);
  };
  const plot::Color ca = category(2), cb = category(5), bg = s.background;
  int one = 0, two = 0;
  double worst = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Ray ray = pixel_ray(cam, x, y, W, H);
      const double ta = hit(ray, a), tb = hit(ray, b);
      if (ta < 0 && tb < 0) continue;
      const auto depth = [&](double t) { return glm::dot(t * ray.d, cam.forward()); };
      double sum_w = 0, reveal = 1, rgb[3] = {0, 0, 0};
      for (auto [t, c] : {std::pair{ta, ca}, std::pair{tb, cb}}) {
        if (t < 0) continue;
        const double w = weight(depth(t));
        sum_w += w;
        reveal *= 1 - alpha;
        rgb[0] += c.r * w;
        rgb[1] += c.g * w;
        rgb[2] += c.b * w;
      }
      const double expect[3] = {rgb[0] / sum_w * (1 - reveal) + bg.r * reveal,
                                rgb[1] / sum_w * (1 - reveal) + bg.g * reveal,
                                rgb[2] / sum_w * (1 - reveal) + bg.b * reveal};
      // skip pixels on an outline (partly covered in one of the two casts)
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const Ray q = pixel_ray(cam, x + dx, y + dy, W, H);
          edge |= (hit(q, a) > 0) != (ta > 0) || (hit(q, b) > 0) != (tb > 0);
        }
      if (edge) continue;
      const plot::Color p = plot::pixel(img, x, y);
      worst = std::max({worst, std::abs(p.r - expect[0]), std::abs(p.g - expect[1]),
                        std::abs(p.b - expect[2])});
      (ta > 0 && tb > 0 ? two : one)++;
    }
  EXPECT_GT(one, 300);
  EXPECT_GT(two, 100);
  EXPECT_LE(worst, 2.0) << "largest channel error in 8-bit levels";
}

// A force chain is a tube on the projected segment, as wide as the
// projection of its documented diameter 2 R_mean max(chain_min_radius,
// chain_radius F/F_max); below the threshold it is not drawn; a wall contact
// has the wall-contact colour; a stronger chain is darker.
TEST(Renderer, ForceChainTubeWhereProjectedWithDocumentedWidth) {
  const Gl& gl = context().gl();
  Renderer r(gl);
  const int W = 400, H = 300;
  r.resize(W, H);
  GeometryBuffers buf(gl);
  Camera cam = axis_camera(0.4);
  ViewSettings s = flat_settings();
  s.show_beads = false;
  s.show_chains = true;
  s.chain_threshold = 0.5f;  // F >= 1 N drawn
  s.chain_radius = 0.45f;
  s.chain_min_radius = 0.1f;
  upload(buf, {{{0, 0, 0}, 0.01f, 0}});  // R_mean = 10 mm: tubes of 4.5 mm at F_max
  // pair 1 horizontal at z = 0.02, F = F_max = 6 N; pair 2 at z = -0.02,
  // F = 3 N; pair 3 vertical at x = 0.045, F = 0.6 N: under the threshold;
  // a wall contact vertical at x = -0.045, F = 6 N
  const float mean = 2.0f, most = 6.0f;
  const std::vector<float> seg = {-0.03f, 0, 0.02f,  6.0f, 0.03f,   0, 0.02f,  0,
                                  -0.03f, 0, -0.02f, 3.0f, 0.03f,   0, -0.02f, 0,
                                  0.045f, 0, -0.03f, 0.6f, 0.045f,  0, 0.03f,  0,
                                  -0.045f, 0, -0.03f, 6.0f, -0.045f, 0, 0.03f, 1};
  buf.upload_segments(seg, mean, most);
  buf.mutable_geometry().lo = {-0.05, -0.01, -0.05};
  buf.mutable_geometry().hi = {0.05, 0.01, 0.05};
  r.draw(cam, buf.geometry(), s);
  const plot::Image img = r.read_pixels();
  for (auto [z, radius] : {std::pair{0.02, 0.0045}, std::pair{-0.02, 0.00225}}) {
    const auto mid = cam.project({0, 0, z}, W, H).pixel;
    const double width = std::abs(cam.project({0, 0, z + radius}, W, H).pixel.y -
                                  cam.project({0, 0, z - radius}, W, H).pixel.y);
    const int x = int(mid.x);
    int covered = 0, first = -1;
    for (int y = 0; y < H; ++y)
      if (!is_background(img, x, y)) {
        if (std::abs(y + 0.5 - mid.y) > 20) continue;
        covered++;
        if (first < 0) first = y;
      }
    EXPECT_NEAR(covered, width, 1.5) << "tube at z = " << z;
    EXPECT_NEAR(first + covered / 2.0, mid.y, 1.0) << "tube at z = " << z;  // centred
    // a round cap: past the end by its radius on the axis, not beyond
    const auto end = cam.project({0.03, 0, z}, W, H).pixel;
    EXPECT_FALSE(is_background(img, int(end.x + 0.5 * width) - 2, int(mid.y)));
    EXPECT_TRUE(is_background(img, int(end.x + 0.5 * width) + 2, int(mid.y)));
  }
  const auto weak = cam.project({0.045, 0, 0}, W, H).pixel;
  for (int dx = -3; dx <= 3; ++dx) EXPECT_TRUE(is_background(img, int(weak.x) + dx, int(weak.y)));
  // on its axis a tube shows its colour: the wall contact the wall-contact colour
  const auto wall = cam.project({-0.045, 0, 0}, W, H).pixel;
  const plot::Color w = plot::pixel(img, int(wall.x), int(wall.y));
  EXPECT_NEAR(w.r, 255 * s.wall_chain_color.r, 3);
  EXPECT_NEAR(w.g, 255 * s.wall_chain_color.g, 3);
  EXPECT_NEAR(w.b, 255 * s.wall_chain_color.b, 3);
  // stronger is lighter (the Glow map): the 6 N chain against the 3 N one
  const auto p1 = cam.project({0, 0, 0.02}, W, H).pixel, p2 = cam.project({0, 0, -0.02}, W, H).pixel;
  const auto c1 = plot::pixel(img, int(p1.x), int(p1.y)), c2 = plot::pixel(img, int(p2.x), int(p2.y));
  EXPECT_GT(c1.r + c1.g + c1.b, c2.r + c2.g + c2.b);
  const plot::Color top = plot::colormap_color(plot::ColorMap::Glow, 1.0);
  EXPECT_NEAR(c1.r, top.r, 3);
  EXPECT_NEAR(c1.g, top.g, 3);
  EXPECT_NEAR(c1.b, top.b, 3);
}

// draw() leaves the caller's framebuffer, viewport, blending and depth state
// as it found them.
TEST(Renderer, RestoresGlState) {
  const Gl& gl = context().gl();
  Renderer r(gl);
  r.resize(64, 48);
  GeometryBuffers buf(gl);
  upload(buf, {{{0, 0, 0}, 0.01f, 1}});
  GLuint fbo = 0, tex = 0;
  gl.GenTextures(1, &tex);
  gl.BindTexture(GL_TEXTURE_2D, tex);
  gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 8, 8, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
  gl.Viewport(1, 2, 5, 6);
  gl.Enable(GL_BLEND);
  gl.BlendFuncSeparate(GL_DST_COLOR, GL_ZERO, GL_ONE, GL_ZERO);
  gl.Disable(GL_DEPTH_TEST);
  ViewSettings s = flat_settings();
  s.mode = ViewMode::Transparent;
  s.show_walls = true;
  buf.mutable_geometry().walls = {{{0, 0.02f, 0}, {0.02f, 0, 0}, {0, 0, 0.02f}}};
  r.draw(axis_camera(0.3), buf.geometry(), s);
  GLint bound = 0, vp[4] = {}, src = 0;
  gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
  gl.GetIntegerv(GL_VIEWPORT, vp);
  gl.GetIntegerv(GL_BLEND_SRC_RGB, &src);
  EXPECT_EQ(GLuint(bound), fbo);
  EXPECT_EQ(vp[0], 1);
  EXPECT_EQ(vp[3], 6);
  EXPECT_EQ(src, GL_DST_COLOR);
  EXPECT_TRUE(gl.IsEnabled(GL_BLEND));
  EXPECT_FALSE(gl.IsEnabled(GL_DEPTH_TEST));
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.DeleteFramebuffers(1, &fbo);
  gl.DeleteTextures(1, &tex);
  gl.Disable(GL_BLEND);
}

TEST(Renderer, BadFrameSizeIsAnError) {
  Renderer r(context().gl());
  EXPECT_THROW(r.resize(0, 10), RenderError);
  EXPECT_THROW(r.resize(10, Renderer::kMaxSize + 1), RenderError);
  try {
    r.resize(-3, 4);
    FAIL() << "a negative width was accepted";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("[1, 16384]"), std::string::npos) << e.what();
  }
}

TEST(Renderer, BothHeadlessBackendsWork) {
  for (GlBackend b : {GlBackend::Egl, GlBackend::OSMesa}) {
    SCOPED_TRACE(to_string(b));
    std::unique_ptr<GlContext> ctx;
    ASSERT_NO_THROW(ctx = create_headless_context(b));
    Renderer r(ctx->gl());
    r.resize(100, 80);
    GeometryBuffers buf(ctx->gl());
    upload(buf, {{{0, 0, 0}, 0.02f, 3}});
    r.draw(axis_camera(0.4), buf.geometry(), flat_settings());
    const plot::Image img = r.read_pixels();
    EXPECT_EQ(plot::pixel(img, 50, 40), category(3));
    EXPECT_TRUE(is_background(img, 2, 2));
  }
  context().make_current();
}

// ------------------------------------------------------------ golden images
// A small fixed scene (a 4 x 4 x 3 lattice of beads, the walls of a box,
// force chains between neighbours) in the three modes, compared with PNGs in
// tests/golden. The tolerance admits rasteriser differences along edges
// (at most 1.5 % of the pixels off by more than 48 levels, mean difference
// under 3 levels); the test also checks that it rejects a camera turned by
// 4 degrees, another colour map (chains mode: missing chains) and a
// missing wall layer.
// SIMSOLS_UPDATE_GOLDEN=1 rewrites the files (after a deliberate change).
namespace {

struct GoldenScene {
  std::vector<Bead> beads;
  std::vector<float> segments;
  std::vector<WallQuad> walls;
};

GoldenScene golden_scene() {
  GoldenScene g;
  const float r = 0.005f, h = 0.0098f;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        g.beads.push_back({{(i - 1.5f) * h + 0.0012f * (k % 2), (j - 1.5f) * h, k * h + r}, r,
                           float(k)});
  for (size_t a = 0; a < g.beads.size(); ++a)
    for (size_t b = a + 1; b < g.beads.size(); ++b) {
      const glm::vec3 pa = g.beads[a].c, pb = g.beads[b].c;
      if (glm::length(pa - pb) > 1.2f * h) continue;
      const float f = 1.0f + 3.0f * std::abs(std::sin(float(a * 7 + b * 3)));
      g.segments.insert(g.segments.end(), {pa.x, pa.y, pa.z, f, pb.x, pb.y, pb.z, 0.f});
    }
  const float L = 2.2f * h, H = 1.6f * h;
  g.walls = {{{0, 0, 0}, {L, 0, 0}, {0, L, 0}},
             {{-L, 0, H}, {0, L, 0}, {0, 0, H}},
             {{L, 0, H}, {0, L, 0}, {0, 0, H}},
             {{0, L, H}, {L, 0, 0}, {0, 0, H}}};
  return g;
}

plot::Image render_golden(GlContext& ctx, ViewMode mode, double yaw_offset = 0,
                          plot::ColorMap map = plot::ColorMap::Categorical, bool walls = true,
                          bool chains = true) {
  Renderer r(ctx.gl());
  r.resize(200, 150);
  GeometryBuffers buf(ctx.gl());
  const GoldenScene g = golden_scene();
  upload(buf, g.beads);
  float mean = 0, most = 0;
  for (size_t k = 3; k < g.segments.size(); k += 8) {
    mean += g.segments[k];
    most = std::max(most, g.segments[k]);
  }
  mean /= float(g.segments.size() / 8);
  buf.upload_segments(g.segments, mean, most);
  buf.mutable_geometry().walls = g.walls;
  buf.mutable_geometry().lo = {-0.025, -0.025, 0};
  buf.mutable_geometry().hi = {0.025, 0.025, 0.035};
  Camera cam;
  cam.set_preset(ViewPreset::ThreeQuarter);
  cam.yaw_deg += yaw_offset;
  cam.fit(buf.geometry().lo, buf.geometry().hi, 200.0 / 150);
  ViewSettings s;
  s.mode = mode;
  s.bead_map = map;
  s.value_min = 0;
  s.value_max = 2;
  s.show_walls = walls;
  s.show_chains = mode == ViewMode::Chains;
  if (!chains) s.chain_threshold = 1e9f;
  r.draw(cam, buf.geometry(), s);
  return r.read_pixels();
}

struct Difference {
  double mean = 0;      // mean absolute difference per channel, levels
  double far = 0;       // fraction of pixels off by more than 48 levels
  bool ok() const { return mean < 3 && far < 0.015; }
};

Difference compare(const plot::Image& a, const plot::Image& b) {
  Difference d;
  if (a.width != b.width || a.height != b.height) return {255, 1};
  long far = 0;
  double sum = 0;
  for (size_t p = 0; p < a.rgba.size(); p += 4) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int e = std::abs(int(a.rgba[p + c]) - int(b.rgba[p + c]));
      sum += e;
      worst = std::max(worst, e);
    }
    far += worst > 48;
  }
  d.mean = sum / (a.rgba.size() / 4 * 3);
  d.far = double(far) / (a.rgba.size() / 4);
  return d;
}

}  // namespace

TEST(Renderer, GoldenImagesAllBackends) {
  const std::filesystem::path dir = SIMSOLS_GOLDEN_DIR;
  const bool update = std::getenv("SIMSOLS_UPDATE_GOLDEN") != nullptr;
  for (ViewMode mode : {ViewMode::Opaque, ViewMode::Transparent, ViewMode::Chains}) {
    const std::string file = (dir / (std::string("lattice_") + to_string(mode) + ".png")).string();
    if (update) {
      plot::write_png(render_golden(context(), mode), file);
      std::printf("updated %s\n", file.c_str());
    }
    ASSERT_TRUE(std::filesystem::exists(file)) << file << " missing (SIMSOLS_UPDATE_GOLDEN=1)";
    const plot::Image golden = plot::read_png(file);
    for (GlBackend b : {GlBackend::Egl, GlBackend::OSMesa}) {
      auto ctx = create_headless_context(b);
      const Difference d = compare(render_golden(*ctx, mode), golden);
      EXPECT_TRUE(d.ok()) << to_string(mode) << " on " << to_string(b) << ": mean " << d.mean
                          << ", far " << d.far;
    }
    context().make_current();
    // the tolerance is not so loose that it misses real mistakes
    EXPECT_FALSE(compare(render_golden(context(), mode, 4.0), golden).ok()) << to_string(mode);
    if (mode == ViewMode::Chains)  // faint beads: the chains are the picture
      EXPECT_FALSE(compare(render_golden(context(), mode, 0, plot::ColorMap::Categorical, true,
                                         false),
                           golden)
                       .ok());
    else
      EXPECT_FALSE(
          compare(render_golden(context(), mode, 0, plot::ColorMap::Sequential), golden).ok())
          << to_string(mode);
    EXPECT_FALSE(compare(render_golden(context(), mode, 0, plot::ColorMap::Categorical, false),
                         golden)
                     .ok())
        << to_string(mode);
  }
}
