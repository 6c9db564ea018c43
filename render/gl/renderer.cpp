#include "render/gl/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/type_ptr.hpp>

#include "render/gl/shader.h"

namespace simsols::render {

const char* to_string(ViewMode m) {
  switch (m) {
    case ViewMode::Opaque: return "opaque";
    case ViewMode::Transparent: return "transparent";
    case ViewMode::Chains: return "chains";
  }
  return "?";
}

std::optional<ViewMode> parse_view_mode(std::string_view s) {
  for (ViewMode m : {ViewMode::Opaque, ViewMode::Transparent, ViewMode::Chains})
    if (s == to_string(m)) return m;
  return std::nullopt;
}

// ------------------------------------------------------- GeometryBuffers

GeometryBuffers::GeometryBuffers(const Gl& gl) : gl_(gl) {
  GLuint b[3];
  gl.GenBuffers(3, b);
  beads_ = b[0];
  values_ = b[1];
  segments_ = b[2];
  geom_.beads = beads_;
  geom_.values = values_;
  geom_.segments = segments_;
}

GeometryBuffers::~GeometryBuffers() {
  const GLuint b[3] = {beads_, values_, segments_};
  gl_.DeleteBuffers(3, b);
}

void GeometryBuffers::reserve(std::size_t beads, std::size_t segments) {
  GLint prev = 0;
  gl_.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev);
  if (beads > bead_cap_) {
    gl_.BindBuffer(GL_ARRAY_BUFFER, beads_);
    gl_.BufferData(GL_ARRAY_BUFFER, beads * 16, nullptr, GL_STREAM_DRAW);
    gl_.BindBuffer(GL_ARRAY_BUFFER, values_);
    gl_.BufferData(GL_ARRAY_BUFFER, beads * 4, nullptr, GL_STREAM_DRAW);
    bead_cap_ = beads;
  }
  if (segments > seg_cap_) {
    gl_.BindBuffer(GL_ARRAY_BUFFER, segments_);
    gl_.BufferData(GL_ARRAY_BUFFER, segments * 32, nullptr, GL_STREAM_DRAW);
    seg_cap_ = segments;
  }
  gl_.BindBuffer(GL_ARRAY_BUFFER, GLuint(prev));
  gl_.check("GeometryBuffers::reserve");
}

void GeometryBuffers::upload_beads(const std::vector<float>& xyzr, const std::vector<float>& values) {
  const std::size_t n = xyzr.size() / 4;
  if (values.size() != n)
    throw RenderError("upload_beads: " + std::to_string(n) + " beads but " +
                      std::to_string(values.size()) + " values");
  reserve(n, 0);
  GLint prev = 0;
  gl_.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev);
  gl_.BindBuffer(GL_ARRAY_BUFFER, beads_);
  if (n) gl_.BufferSubData(GL_ARRAY_BUFFER, 0, n * 16, xyzr.data());
  gl_.BindBuffer(GL_ARRAY_BUFFER, values_);
  if (n) gl_.BufferSubData(GL_ARRAY_BUFFER, 0, n * 4, values.data());
  gl_.BindBuffer(GL_ARRAY_BUFFER, GLuint(prev));
  geom_.bead_count = n;
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k) sum += xyzr[4 * k + 3];
  geom_.bead_radius = n ? float(sum / double(n)) : 0.f;
}

void GeometryBuffers::upload_segments(const std::vector<float>& segments, float mean_force,
                                      float max_force) {
  const std::size_t n = segments.size() / 8;
  reserve(0, n);
  GLint prev = 0;
  gl_.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &prev);
  gl_.BindBuffer(GL_ARRAY_BUFFER, segments_);
  if (n) gl_.BufferSubData(GL_ARRAY_BUFFER, 0, n * 32, segments.data());
  gl_.BindBuffer(GL_ARRAY_BUFFER, GLuint(prev));
  geom_.segment_count = n;
  geom_.mean_force = mean_force;
  geom_.max_force = max_force;
}

ForceRange chain_force_range(const ViewSettings& s, const FrameGeometry& g) {
  const float lo = s.chain_threshold * g.mean_force;
  return {lo, std::max(g.max_force, lo)};
}

// -------------------------------------------------------------- Renderer

namespace {

// Saves the GL state a frame touches and puts it back on destruction.
class StateGuard {
 public:
  explicit StateGuard(const Gl& gl) : gl_(gl) {
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fbo_);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo_);
    gl.GetIntegerv(GL_VIEWPORT, viewport_);
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &program_);
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
    gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &array_buffer_);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &texture0_);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &texture1_);
    gl.GetIntegerv(GL_BLEND_SRC_RGB, &blend_[0]);
    gl.GetIntegerv(GL_BLEND_DST_RGB, &blend_[1]);
    gl.GetIntegerv(GL_BLEND_SRC_ALPHA, &blend_[2]);
    gl.GetIntegerv(GL_BLEND_DST_ALPHA, &blend_[3]);
    gl.GetIntegerv(GL_DEPTH_FUNC, &depth_func_);
    GLint mask = 0;
    gl.GetIntegerv(GL_DEPTH_WRITEMASK, &mask);
    depth_mask_ = mask != 0;
    blend_on_ = gl.IsEnabled(GL_BLEND);
    depth_on_ = gl.IsEnabled(GL_DEPTH_TEST);
    cull_on_ = gl.IsEnabled(GL_CULL_FACE);
    scissor_on_ = gl.IsEnabled(GL_SCISSOR_TEST);
  }
  ~StateGuard() {
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_fbo_));
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_fbo_));
    gl_.Viewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    gl_.UseProgram(GLuint(program_));
    gl_.BindVertexArray(GLuint(vao_));
    gl_.BindBuffer(GL_ARRAY_BUFFER, GLuint(array_buffer_));
    gl_.ActiveTexture(GL_TEXTURE1);
    gl_.BindTexture(GL_TEXTURE_2D, GLuint(texture1_));
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_2D, GLuint(texture0_));
    gl_.ActiveTexture(GLenum(active_texture_));
    gl_.BlendFuncSeparate(blend_[0], blend_[1], blend_[2], blend_[3]);
    gl_.DepthFunc(GLenum(depth_func_));
    gl_.DepthMask(depth_mask_ ? GL_TRUE : GL_FALSE);
    toggle(GL_BLEND, blend_on_);
    toggle(GL_DEPTH_TEST, depth_on_);
    toggle(GL_CULL_FACE, cull_on_);
    toggle(GL_SCISSOR_TEST, scissor_on_);
  }

 private:
  void toggle(GLenum cap, bool on) { on ? gl_.Enable(cap) : gl_.Disable(cap); }
  const Gl& gl_;
  GLint draw_fbo_ = 0, read_fbo_ = 0, viewport_[4] = {}, program_ = 0, vao_ = 0, array_buffer_ = 0;
  GLint active_texture_ = GL_TEXTURE0, texture0_ = 0, texture1_ = 0, blend_[4] = {}, depth_func_ = 0;
  bool depth_mask_ = true, blend_on_ = false, depth_on_ = false, cull_on_ = false, scissor_on_ = false;
};

GLuint make_texture(const Gl& gl, GLint internal, int w, int h, GLenum format, GLenum type) {
  GLuint t = 0;
  gl.GenTextures(1, &t);
  gl.BindTexture(GL_TEXTURE_2D, t);
  gl.TexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, type, nullptr);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

void check_framebuffer(const Gl& gl, const char* what) {
  const GLenum st = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
  if (st != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", st);
    throw RenderError(std::string(what) + " framebuffer incomplete (status " + code + ")");
  }
}

}  // namespace

Renderer::Renderer(const Gl& gl) : gl_(gl) {
  sphere_ = std::make_unique<ShaderProgram>(gl, "sphere.vert", "sphere.frag");
  sphere_oit_ = std::make_unique<ShaderProgram>(gl, "sphere.vert", "sphere.frag",
                                                std::vector<std::string>{"OIT"});
  segment_ = std::make_unique<ShaderProgram>(gl, "segment.vert", "segment.frag");
  wall_oit_ = std::make_unique<ShaderProgram>(gl, "wall.vert", "wall.frag",
                                              std::vector<std::string>{"OIT"});
  wall_ = std::make_unique<ShaderProgram>(gl, "wall.vert", "wall.frag");
  composite_ = std::make_unique<ShaderProgram>(gl, "fullscreen.vert", "oit_composite.frag");
  gl.GenVertexArrays(1, &vao_);
  gl.GenVertexArrays(1, &empty_vao_);
  gl.GenBuffers(1, &edge_buffer_);
  gl.check("Renderer setup");
}

Renderer::~Renderer() {
  release_targets();
  for (auto& [map, t] : maps_) gl_.DeleteTextures(1, &t.tex);
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteVertexArrays(1, &empty_vao_);
  gl_.DeleteBuffers(1, &edge_buffer_);
}

void Renderer::release_targets() {
  if (scene_fbo_) gl_.DeleteFramebuffers(1, &scene_fbo_);
  if (oit_fbo_) gl_.DeleteFramebuffers(1, &oit_fbo_);
  const GLuint tex[3] = {color_tex_, accum_tex_, weight_tex_};
  for (GLuint t : tex)
    if (t) gl_.DeleteTextures(1, &t);
  if (depth_rb_) {
    // depth is a texture too (the Alioscopy views sample it later)
    gl_.DeleteTextures(1, &depth_rb_);
  }
  scene_fbo_ = oit_fbo_ = color_tex_ = accum_tex_ = weight_tex_ = depth_rb_ = 0;
}

void Renderer::resize(int width, int height) {
  if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize)
    throw RenderError("frame size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is out of range: each side must be in [1, " + std::to_string(kMaxSize) + "]");
  if (width == width_ && height == height_) return;
  StateGuard guard(gl_);
  release_targets();
  width_ = width;
  height_ = height;
  color_tex_ = make_texture(gl_, GL_RGBA8, width, height, GL_RGBA, GL_UNSIGNED_BYTE);
  depth_rb_ = make_texture(gl_, GL_DEPTH_COMPONENT24, width, height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT);
  accum_tex_ = make_texture(gl_, GL_RGBA16F, width, height, GL_RGBA, GL_FLOAT);
  weight_tex_ = make_texture(gl_, GL_R16F, width, height, GL_RED, GL_FLOAT);
  gl_.GenFramebuffers(1, &scene_fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_tex_, 0);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_rb_, 0);
  check_framebuffer(gl_, "scene");
  gl_.GenFramebuffers(1, &oit_fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, oit_fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, accum_tex_, 0);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, weight_tex_, 0);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_rb_, 0);
  const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl_.DrawBuffers(2, bufs);
  check_framebuffer(gl_, "transparency");
  gl_.check("Renderer::resize");
}

void Renderer::bind_colormap(ShaderProgram& p, plot::ColorMap map) {
  auto it = maps_.find(map);
  if (it == maps_.end()) {
    const std::vector<std::uint8_t> table = plot::colormap_table(map);
    MapTexture t;
    t.size = int(table.size() / 4);
    t.tex = make_texture(gl_, GL_RGBA8, t.size, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    gl_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t.size, 1, GL_RGBA, GL_UNSIGNED_BYTE, table.data());
    it = maps_.emplace(map, t).first;
  }
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, it->second.tex);
  p.set("u_colormap", 0);
  p.set("u_colormap_size", it->second.size);
  p.set("u_categorical", map == plot::ColorMap::Categorical   ? 1
                         : map == plot::ColorMap::Qualitative ? 2
                                                              : 0);
}

void Renderer::set_common(ShaderProgram& p, const ViewSettings& s, bool force_map) {
  p.use();
  p.set_mat4("u_view", glm::value_ptr(view_));
  p.set_mat4("u_proj", glm::value_ptr(proj_));
  p.set("u_ortho", ortho_ ? 1 : 0);
  p.set("u_viewport", float(width_), float(height_));
  p.set("u_depth_range", depth_range_.x, depth_range_.y);
  p.set("u_range", s.value_min, s.value_max);
  p.set("u_section", section_.x, section_.y, section_.z, section_.w);
  p.set("u_section_offset", section_offset_);
  bind_colormap(p, force_map ? kChainMap : s.bead_map);
}

void Renderer::draw(const Camera& camera, const FrameGeometry& g, const ViewSettings& s) {
  if (width_ == 0) throw RenderError("Renderer::draw before resize()");
  draw(ViewProjection::of(camera, double(width_) / height_), g, s);
}

void Renderer::draw(const ViewProjection& vp, const FrameGeometry& g, const ViewSettings& s) {
  if (width_ == 0) throw RenderError("Renderer::draw before resize()");
  StateGuard guard(gl_);
  view_ = glm::mat4(vp.view);
  proj_ = glm::mat4(vp.projection);
  ortho_ = vp.orthographic;
  // Depth range of the scene for the OIT weight: view depths of the corners.
  double dmin = 1e300, dmax = -1e300;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c((k & 1) ? g.hi.x : g.lo.x, (k & 2) ? g.hi.y : g.lo.y, (k & 4) ? g.hi.z : g.lo.z);
    const double d = -(vp.view * glm::dvec4(c, 1)).z;
    dmin = std::min(dmin, d);
    dmax = std::max(dmax, d);
  }
  depth_range_ = glm::vec2(float(dmin), float(std::max(dmax, dmin + 1e-9)));
  set_section(g, s);

  gl_.BindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
  gl_.Viewport(0, 0, width_, height_);
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.Disable(GL_CULL_FACE);
  gl_.DepthMask(GL_TRUE);
  const plot::Color bg = s.background;
  gl_.ClearColor(bg.r / 255.f, bg.g / 255.f, bg.b / 255.f, 1.f);
  gl_.ClearDepth(1.0);
  gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  draw_opaque(g, s);
  const bool transparent_beads = s.show_beads && s.mode != ViewMode::Opaque && g.bead_count > 0;
  const bool walls = s.show_walls && !g.walls.empty();
  if (!transparent_beads && walls) {
    draw_walls_blended(g, s);
  } else if (transparent_beads) {
    draw_transparent(g, s);
    composite();
  }
  gl_.check("Renderer::draw");
}

std::string parse_section(const std::string& text, Section& s) {
  if (text == "off") {
    s.axis = -1;
    return {};
  }
  const std::string axes = "xyz";
  const size_t colon = text.find(':');
  const std::string axis = text.substr(0, colon);
  if (axis.size() != 1 || axes.find(axis[0]) == std::string::npos)
    return "'" + text + "' is not AXIS[:WIDTH] with AXIS one of x, y, z (e.g. y or y:1.5), or off";
  float width = s.width;
  if (colon != std::string::npos) {
    char extra = 0;
    if (std::sscanf(text.c_str() + colon + 1, "%f%c", &width, &extra) != 1 ||
        !std::isfinite(width) || !(width > 0) || width > 1000)
      return "'" + text + "': the width must be a number of bead diameters in (0, 1000]";
  }
  s.axis = int(axes.find(axis[0]));
  s.width = width;
  return {};
}

std::string section_text(const Section& s) {
  if (!s.on()) return "off";
  char text[32];
  std::snprintf(text, sizeof text, "%c:%g", "xyz"[s.axis], double(s.width));
  return text;
}

void Renderer::set_section(const FrameGeometry& g, const ViewSettings& s) {
  section_ = glm::vec4(0);
  section_offset_ = 0;
  if (!s.section.on()) return;
  const int a = s.section.axis;
  section_[a] = 1;
  section_.w = std::max(s.section.width, 0.f) * g.bead_radius;  // half of width x 2r
  section_offset_ = float(0.5 * (g.lo[a] + g.hi[a]));
}

void Renderer::draw_beads(ShaderProgram& p, const FrameGeometry& g, const ViewSettings& s, float alpha) {
  set_common(p, s, false);
  p.set("u_lighting", s.lighting ? 1 : 0);
  p.set("u_alpha", alpha);
  // chains mode: every bead the same faint colour, so the chains carry the colour
  const bool ghost = s.mode == ViewMode::Chains;
  p.set("u_flat_color", s.ghost_color.r, s.ghost_color.g, s.ghost_color.b, ghost ? 1.f : 0.f);
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, g.beads);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 16, nullptr);
  gl_.VertexAttribDivisor(0, 1);
  gl_.BindBuffer(GL_ARRAY_BUFFER, g.values);
  gl_.EnableVertexAttribArray(1);
  gl_.VertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 4, nullptr);
  gl_.VertexAttribDivisor(1, 1);
  gl_.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(g.bead_count));
}

// Segments: two float4 per instance (end xyz + force), a quad each.
void Renderer::draw_segments(GLuint buffer, std::size_t count) {
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, buffer);
  for (GLuint a = 0; a < 2; ++a) {
    gl_.EnableVertexAttribArray(a);
    gl_.VertexAttribPointer(a, 4, GL_FLOAT, GL_FALSE, 32, reinterpret_cast<void*>(std::size_t(16 * a)));
    gl_.VertexAttribDivisor(a, 1);
  }
  gl_.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count));
}

void Renderer::draw_opaque(const FrameGeometry& g, const ViewSettings& s) {
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
  gl_.DepthMask(GL_TRUE);
  gl_.Disable(GL_BLEND);
  if (s.show_beads && s.mode == ViewMode::Opaque && g.bead_count > 0) draw_beads(*sphere_, g, s, 1.f);

  if (s.chains_visible() && g.segment_count > 0) {
    set_common(*segment_, s, true);
    const ForceRange range = chain_force_range(s, g);
    segment_->set("u_force_range", range.min, range.max);
    segment_->set("u_tube_radius", g.bead_radius * s.chain_radius,
                  g.bead_radius * s.chain_min_radius);
    segment_->set("u_wall_color", s.wall_chain_color.r, s.wall_chain_color.g, s.wall_chain_color.b,
                  1.f);
    segment_->set("u_fixed_width_px", 0.f);
    draw_segments(g.segments, g.segment_count);
  }

  // Wall edges: the four sides of each rectangle as fixed-width segments.
  if (s.show_walls && s.wall_edge_px > 0 && !g.walls.empty()) {
    std::vector<float> edges;
    edges.reserve(g.walls.size() * 32);
    for (const WallQuad& w : g.walls) {
      const glm::vec3 c[4] = {w.centre - w.axis_u - w.axis_v, w.centre + w.axis_u - w.axis_v,
                              w.centre + w.axis_u + w.axis_v, w.centre - w.axis_u + w.axis_v};
      for (int k = 0; k < 4; ++k) {
        const glm::vec3 a = c[k], b = c[(k + 1) % 4];
        edges.insert(edges.end(), {a.x, a.y, a.z, 0.f, b.x, b.y, b.z, 0.f});
      }
    }
    set_common(*segment_, s, true);
    segment_->set("u_fixed_width_px", s.wall_edge_px);
    segment_->set("u_fixed_color", s.wall_edge_color.r, s.wall_edge_color.g, s.wall_edge_color.b,
                  s.wall_edge_color.a);
    gl_.BindBuffer(GL_ARRAY_BUFFER, edge_buffer_);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(edges.size() * 4), edges.data(), GL_STREAM_DRAW);
    draw_segments(edge_buffer_, edges.size() / 8);
  }
}

void Renderer::draw_transparent(const FrameGeometry& g, const ViewSettings& s) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, oit_fbo_);
  const float accum_clear[4] = {0, 0, 0, 1}, weight_clear[4] = {0, 0, 0, 0};
  gl_.ClearBufferfv(GL_COLOR, 0, accum_clear);
  gl_.ClearBufferfv(GL_COLOR, 1, weight_clear);
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
  gl_.DepthMask(GL_FALSE);  // tested against the opaque stage, never written
  gl_.Enable(GL_BLEND);
  gl_.BlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);

  if (s.show_beads && s.mode != ViewMode::Opaque && g.bead_count > 0)
    draw_beads(*sphere_oit_, g, s, s.mode == ViewMode::Chains ? s.chains_bead_alpha : s.bead_alpha);
  if (s.show_walls) draw_walls(*wall_oit_, g.walls, s);
  gl_.DepthMask(GL_TRUE);
}

void Renderer::draw_walls(ShaderProgram& p, const std::vector<WallQuad>& walls, const ViewSettings& s) {
  set_common(p, s, false);
  p.set("u_color", s.wall_color.r, s.wall_color.g, s.wall_color.b, s.wall_color.a);
  gl_.BindVertexArray(empty_vao_);
  for (const WallQuad& w : walls) {
    p.set("u_centre", w.centre.x, w.centre.y, w.centre.z);
    p.set("u_axis_u", w.axis_u.x, w.axis_u.y, w.axis_u.z);
    p.set("u_axis_v", w.axis_v.x, w.axis_v.y, w.axis_v.z);
    gl_.DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  }
}

// Walls over opaque beads: plates of one colour and opacity, blended
// straight into the frame. Where k plates overlap this gives
// C (1 - (1 - a)^k) + C_0 (1 - a)^k in any order, the OIT formula's value
// for equal colours, without the float targets and the resolve pass (on
// llvmpipe those cost more than the beads).
void Renderer::draw_walls_blended(const FrameGeometry& g, const ViewSettings& s) {
  gl_.Enable(GL_DEPTH_TEST);
  gl_.DepthFunc(GL_LESS);
  gl_.DepthMask(GL_FALSE);
  gl_.Enable(GL_BLEND);
  gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  draw_walls(*wall_, g.walls, s);
  gl_.DepthMask(GL_TRUE);
}

void Renderer::composite() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Enable(GL_BLEND);
  gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  composite_->use();
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, accum_tex_);
  gl_.ActiveTexture(GL_TEXTURE1);
  gl_.BindTexture(GL_TEXTURE_2D, weight_tex_);
  composite_->set("u_accum", 0);
  composite_->set("u_weight", 1);
  gl_.BindVertexArray(empty_vao_);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  gl_.ActiveTexture(GL_TEXTURE0);
}

plot::Image read_framebuffer(const Gl& gl, GLuint fbo, int width, int height, GLenum buffer) {
  plot::Image img;
  img.width = width;
  img.height = height;
  img.rgba.resize(std::size_t(width) * height * 4);
  std::vector<std::uint8_t> rows(img.rgba.size());
  GLint prev = 0, pack = 4;
  gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &prev);
  gl.GetIntegerv(GL_PACK_ALIGNMENT, &pack);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  gl.ReadBuffer(buffer);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  gl.PixelStorei(GL_PACK_ALIGNMENT, pack);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(prev));
  gl.check("read_framebuffer");
  const std::size_t stride = std::size_t(width) * 4;
  for (int y = 0; y < height; ++y)  // GL rows start at the bottom
    std::copy_n(&rows[std::size_t(height - 1 - y) * stride], stride, &img.rgba[std::size_t(y) * stride]);
  return img;
}

plot::Image Renderer::read_pixels() const { return read_framebuffer(gl_, scene_fbo_, width_, height_); }

}  // namespace simsols::render
