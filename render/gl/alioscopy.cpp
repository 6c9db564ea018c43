#include "render/gl/alioscopy.h"

#include <cmath>
#include <stdexcept>

#include "render/gl/shader.h"

namespace simsols::render {

glm::ivec2 DisplayProfile::view_size(int output_width, int output_height) const {
  return {std::max(1, int(std::ceil(output_width * view_scale))),
          std::max(1, int(std::ceil(output_height * view_scale)))};
}

int alioscopy_view(int x, int y, int c, const DisplayProfile& p) {
  const int s = (p.flip_slant ? -y : y) - (3 * x + c) + p.phase;
  const int v = ((s % 8) + 8) % 8;
  return p.reversed ? 7 - v : v;
}

plot::Image deinterleave(const plot::Image& in, int k, const DisplayProfile& p, glm::ivec2 window) {
  plot::Image out = in;
  for (int y = 0; y < in.height; ++y)
    for (int c = 0; c < 3; ++c) {
      // the columns of this row whose channel c shows view k: one every 8
      int first = -1;
      for (int x = 0; x < std::min(8, in.width); ++x)
        if (alioscopy_view(window.x + x, window.y + y, c, p) == k) first = x;
      for (int x = 0; x < in.width; ++x) {
        int src = first;
        if (first >= 0) {
          // nearest column congruent to `first` modulo 8
          const int base = x - ((x - first) % 8 + 8) % 8;
          src = (x - base <= 4 || base + 8 >= in.width) ? base : base + 8;
          if (src < 0) src += 8;
        }
        const std::size_t o = (std::size_t(y) * in.width + x) * 4 + c;
        out.rgba[o] = src >= 0 && src < in.width ? in.rgba[(std::size_t(y) * in.width + src) * 4 + c] : 0;
      }
    }
  return out;
}

AlioscopyOutput::AlioscopyOutput(const Gl& gl, const DisplayProfile& profile)
    : gl_(gl), profile_(profile) {
  program_ = std::make_unique<ShaderProgram>(gl, "fullscreen.vert", "alioscopy.frag");
  GLint prev_tex = 0;
  gl.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &prev_tex);
  gl.GenTextures(1, &views_tex_);
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, views_tex_);
  const GLint filter = profile.nearest_views ? GL_NEAREST : GL_LINEAR;
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, filter);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, filter);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, GLuint(prev_tex));
  gl.GenFramebuffers(1, &layer_fbo_);
  gl.GenVertexArrays(1, &vao_);
  resize_output(profile.width, profile.height);
  gl.check("AlioscopyOutput setup");
}

AlioscopyOutput::~AlioscopyOutput() {
  gl_.DeleteTextures(1, &views_tex_);
  gl_.DeleteTextures(1, &out_tex_);
  gl_.DeleteFramebuffers(1, &layer_fbo_);
  gl_.DeleteFramebuffers(1, &out_fbo_);
  gl_.DeleteVertexArrays(1, &vao_);
}

void AlioscopyOutput::resize_output(int width, int height) {
  if (width < 1 || height < 1 || width > Renderer::kMaxSize || height > Renderer::kMaxSize)
    throw RenderError("Alioscopy output " + std::to_string(width) + "x" + std::to_string(height) +
                      " is out of range: each side must be in [1, " +
                      std::to_string(Renderer::kMaxSize) + "]");
  if (width == out_w_ && height == out_h_) return;
  GLint prev_fbo = 0, prev_tex = 0, prev_array = 0;
  gl_.GetIntegerv(GL_FRAMEBUFFER_BINDING, &prev_fbo);
  gl_.GetIntegerv(GL_TEXTURE_BINDING_2D, &prev_tex);
  gl_.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &prev_array);
  view_ = profile_.view_size(width, height);
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, views_tex_);
  gl_.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, view_.x, view_.y, profile_.views, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, nullptr);
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, GLuint(prev_array));
  if (out_tex_) gl_.DeleteTextures(1, &out_tex_);
  if (out_fbo_) gl_.DeleteFramebuffers(1, &out_fbo_);
  gl_.GenTextures(1, &out_tex_);
  gl_.BindTexture(GL_TEXTURE_2D, out_tex_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.GenFramebuffers(1, &out_fbo_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, out_fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, out_tex_, 0);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RenderError("Alioscopy output framebuffer incomplete");
  gl_.BindFramebuffer(GL_FRAMEBUFFER, GLuint(prev_fbo));
  gl_.BindTexture(GL_TEXTURE_2D, GLuint(prev_tex));
  out_w_ = width;
  out_h_ = height;
}

void AlioscopyOutput::copy_view(int k, const Renderer& renderer) {
  if (k < 0 || k >= profile_.views) throw RenderError("view " + std::to_string(k) + " out of range");
  GLint read = 0, draw = 0;
  gl_.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  gl_.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, renderer.framebuffer());
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, layer_fbo_);
  gl_.FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, views_tex_, 0, k);
  const bool same = renderer.width() == view_.x && renderer.height() == view_.y;
  gl_.BlitFramebuffer(0, 0, renderer.width(), renderer.height(), 0, 0, view_.x, view_.y,
                      GL_COLOR_BUFFER_BIT, same ? GL_NEAREST : GL_LINEAR);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read));
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw));
  gl_.check("AlioscopyOutput::copy_view");
}

void AlioscopyOutput::fill_view(int k, glm::vec4 rgba) {
  GLint draw = 0;
  gl_.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, layer_fbo_);
  gl_.FramebufferTextureLayer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, views_tex_, 0, k);
  const float c[4] = {rgba.r, rgba.g, rgba.b, rgba.a};
  gl_.ClearBufferfv(GL_COLOR, 0, c);
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw));
}

void AlioscopyOutput::upload_view(int k, const plot::Image& img) {
  if (k < 0 || k >= profile_.views) throw RenderError("view " + std::to_string(k) + " out of range");
  if (img.width != view_.x || img.height != view_.y)
    throw RenderError("upload_view: image " + std::to_string(img.width) + "x" +
                      std::to_string(img.height) + ", views are " +
                      std::to_string(view_.x) + "x" + std::to_string(view_.y));
  std::vector<std::uint8_t> rows(img.rgba.size());
  const std::size_t stride = std::size_t(img.width) * 4;
  for (int y = 0; y < img.height; ++y)  // GL rows start at the bottom
    std::copy_n(&img.rgba[std::size_t(img.height - 1 - y) * stride], stride, &rows[y * stride]);
  GLint tex = 0, unpack = 4;
  gl_.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &tex);
  gl_.GetIntegerv(GL_UNPACK_ALIGNMENT, &unpack);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, views_tex_);
  gl_.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, k, img.width, img.height, 1, GL_RGBA,
                    GL_UNSIGNED_BYTE, rows.data());
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, GLuint(tex));
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, unpack);
  gl_.check("AlioscopyOutput::upload_view");
}

StereoRig DisplayProfile::rig(const StereoRig& rig_in) const {
  StereoRig rig = rig_in;
  rig.views = views;
  if (rig.interaxial <= 0) rig.interaxial = interaxial;
  if (rig.focus <= 0) rig.focus = focus;
  if (rig.interaxial <= 0) rig.ratio = interaxial_ratio;
  return rig;
}

void AlioscopyOutput::render_views(Renderer& renderer, const StereoRig& rig_in,
                                   const Camera& camera, const FrameGeometry& geometry,
                                   const ViewSettings& settings) {
  const StereoRig views = profile_.rig(rig_in);
  renderer.resize(view_.x, view_.y);
  const double aspect = double(out_w_) / out_h_;  // the views fill the screen
  for (int k = 0; k < profile_.views; ++k) {
    renderer.draw(views.view(camera, k, aspect), geometry, settings);
    copy_view(k, renderer);
  }
}

namespace {
// The size of a view of `aspect` fitted in a cell of cw x ch.
std::pair<double, double> fitted(double cw, double ch, double aspect) {
  return aspect > cw / ch ? std::pair{cw, cw / aspect} : std::pair{ch * aspect, ch};
}
}  // namespace

GridLayout grid_layout(int width, int height, double aspect) {
  GridLayout best;
  double most = -1;
  for (int columns = 1; columns <= kAlioscopyViews; ++columns) {
    const int rows = (kAlioscopyViews + columns - 1) / columns;
    const auto [w, h] = fitted(double(width) / columns, double(height) / rows, aspect);
    if (w * h > most * (1 + 1e-9)) {
      most = w * h;
      best = {columns, rows};
    }
  }
  return best;
}

plot::Rect GridLayout::cell(int k, int width, int height, double aspect) const {
  const double cw = double(width) / columns, ch = double(height) / rows;
  const auto [w, h] = fitted(cw, ch, aspect);
  const double x0 = (k % columns) * cw + 0.5 * (cw - w), y0 = (k / columns) * ch + 0.5 * (ch - h);
  return {int(std::lround(x0)), int(std::lround(y0)), int(std::lround(x0 + w)), int(std::lround(y0 + h))};
}

GridLayout AlioscopyOutput::grid() const {
  return grid_layout(out_w_, out_h_, double(out_w_) / std::max(1, out_h_));
}

void AlioscopyOutput::compose(Mode mode, int single_view, glm::ivec2 window) {
  compose_into(out_fbo_, {0, 0}, mode, single_view, window);
}

void AlioscopyOutput::compose_into(GLuint fbo_target, glm::ivec2 at, Mode mode, int single_view,
                                   glm::ivec2 window) {
  GLint fbo = 0, vp[4] = {}, program = 0, vao = 0, active = 0, tex = 0;
  gl_.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
  gl_.GetIntegerv(GL_VIEWPORT, vp);
  gl_.GetIntegerv(GL_CURRENT_PROGRAM, &program);
  gl_.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
  gl_.GetIntegerv(GL_ACTIVE_TEXTURE, &active);
  const bool blend = gl_.IsEnabled(GL_BLEND), depth = gl_.IsEnabled(GL_DEPTH_TEST);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &tex);

  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_target);
  gl_.Viewport(at.x, at.y, out_w_, out_h_);
  gl_.Disable(GL_BLEND);  // written 1:1: nothing blends, filters or scales
  gl_.Disable(GL_DEPTH_TEST);
  program_->use();
  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, views_tex_);
  program_->set("u_views", 0);
  gl_.Uniform2i(program_->uniform("u_output"), out_w_, out_h_);
  gl_.Uniform2i(program_->uniform("u_origin"), at.x, at.y);
  gl_.Uniform2i(program_->uniform("u_view_size"), view_.x, view_.y);
  gl_.Uniform2i(program_->uniform("u_window"), window.x, window.y);
  program_->set("u_phase", profile_.phase);
  program_->set("u_reversed", profile_.reversed ? 1 : 0);
  program_->set("u_flip_slant", profile_.flip_slant ? 1 : 0);
  program_->set("u_mode", int(mode));
  program_->set("u_single", std::clamp(single_view, 0, profile_.views - 1));
  const GridLayout g = grid();
  gl_.Uniform2i(program_->uniform("u_grid"), g.columns, g.rows);
  gl_.BindVertexArray(vao_);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);

  gl_.BindTexture(GL_TEXTURE_2D_ARRAY, GLuint(tex));
  gl_.ActiveTexture(GLenum(active));
  gl_.BindVertexArray(GLuint(vao));
  gl_.UseProgram(GLuint(program));
  gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(fbo));
  gl_.Viewport(vp[0], vp[1], vp[2], vp[3]);
  if (blend) gl_.Enable(GL_BLEND);
  if (depth) gl_.Enable(GL_DEPTH_TEST);
  gl_.check("AlioscopyOutput::compose");
}

plot::Image AlioscopyOutput::read_pixels() const { return read_framebuffer(gl_, out_fbo_, out_w_, out_h_); }

plot::Image AlioscopyOutput::read_view(int k) const {
  GLint read = 0;
  gl_.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, layer_fbo_);
  gl_.FramebufferTextureLayer(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, views_tex_, 0, k);
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read));
  return read_framebuffer(gl_, layer_fbo_, view_.x, view_.y);
}

}  // namespace simsols::render
