// Renderer: draws one frame of a granular specimen into its own offscreen
// framebuffer (OpenGL 3.3 core), in stages read in order:
//
//   draw_opaque       beads as lit sphere impostors (opaque mode), force
//                     chains, wall edges; depth written
//   draw_transparent  beads (transparent and chains modes) and the walls
//                     into weighted blended OIT targets, depth-tested
//                     against the opaque stage, nothing sorted
//   composite         resolves the transparent layer over the opaque image
//   (opaque mode: the walls alone are translucent; draw_walls_blended puts
//   them straight over the frame instead of the two stages)
//
// Inputs are GL buffers (FrameGeometry) that the data path fills either
// through OpenCL-OpenGL sharing or one host copy; the renderer does not know
// which. No globals: the GL function table comes with the context, and every
// piece of GL state a frame changes is restored when draw() returns (framebuffer,
// viewport, program, vertex array, blend and depth state), as Dear ImGui's
// renderer backends do, so a window's UI can draw over the result.
//
// Formulas (docs/rendering.md):
//   bead:  exact ray-sphere hit, Lambert + ambient + Blinn highlight
//   chain: a tube (shaded screen-space capsule) of radius
//          r = R_mean max(chain_min_radius, chain_radius F/F_max), drawn where
//          F/F_mean >= chain_threshold; bead pairs coloured by the Glow map
//          at t = (F - F_thr)/(F_max - F_thr), F_thr = chain_threshold F_mean;
//          wall contacts in wall_chain_color
//   OIT:   C = (sum C_i a_i w_i / sum a_i w_i)(1 - prod(1 - a_i)) + C_0 prod(1 - a_i),
//          w_i = a_i max(0.01, 100 (1 - d_i)^3), d_i the depth in the scene's range
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string_view>
#include <memory>
#include <string>
#include <vector>

#include "render/gl/camera.h"
#include "render/plot/colormap.h"
#include "render/gl/gl_api.h"
#include "render/plot/image.h"

namespace simsols::render {

class ShaderProgram;

// A rectangle of the apparatus: centre +- axis_u +- axis_v (half extents
// included), in the render frame (positions relative to the render origin).
struct WallQuad {
  glm::vec3 centre{}, axis_u{}, axis_v{};
};

// GL buffers with what to draw. beads: float4 (x, y, z, radius) per bead;
// values: one float per bead (the colour field); segments: two float4
// (a.xyz, |F_n|), (b.xyz, kind: 0 bead pair, 1 wall contact) per contact.
struct FrameGeometry {
  GLuint beads = 0, values = 0;
  std::size_t bead_count = 0;
  GLuint segments = 0;
  std::size_t segment_count = 0;
  float mean_force = 0;   // N, over all contacts (the chain threshold)
  float max_force = 0;    // N, over all contacts (the widest chain, the top of the colour bar)
  float bead_radius = 0;  // m, the beads' mean radius (the chains' width scale)
  std::vector<WallQuad> walls;
  glm::dvec3 lo{0}, hi{0};  // bounds of everything drawn (depth range of the OIT weight)
};

enum class ViewMode { Opaque, Transparent, Chains };
const char* to_string(ViewMode m);  // "opaque", "transparent", "chains"
std::optional<ViewMode> parse_view_mode(std::string_view s);

// A slab through the middle of what is drawn: only the beads whose centres
// lie within width / 2 of the plane normal to `axis` (0 x, 1 y, 2 z), and
// the force chains whose midpoints do, are drawn (the walls stay whole);
// axis -1: the whole specimen. Width in mean bead diameters.
struct Section {
  int axis = -1;
  float width = 2.0f;
  bool on() const { return axis >= 0 && axis <= 2; }
};

struct ViewSettings {
  ViewMode mode = ViewMode::Opaque;
  float bead_alpha = 0.3f;          // transparent mode
  float chains_bead_alpha = 0.07f;  // chains mode: faint beads around the chains
  glm::vec3 ghost_color{0.72f, 0.75f, 0.80f};  // chains mode: the faint beads' colour
  bool lighting = true;
  bool show_beads = true;
  bool show_walls = true;
  bool show_chains = false;  // overlay in any mode; always on in chains mode
  float chain_threshold = 1.0f;   // F/F_mean below which a contact is not drawn
  float chain_radius = 0.45f;     // tube radius at F_max, in mean bead radii
  float chain_min_radius = 0.1f;  // the thinnest tube, in mean bead radii
  glm::vec3 wall_chain_color{0.45f, 0.48f, 0.54f};  // bead-wall contacts
  plot::ColorMap bead_map = plot::ColorMap::Sequential;
  float value_min = 0, value_max = 1;
  plot::Color background{22, 24, 28};
  glm::vec4 wall_color{0.62f, 0.68f, 0.76f, 0.14f};
  glm::vec4 wall_edge_color{0.70f, 0.75f, 0.82f, 1.0f};
  float wall_edge_px = 1.5f;  // 0: no edges
  Section section;
  bool chains_visible() const { return show_chains || mode == ViewMode::Chains; }
};

// Reads a section "AXIS[:WIDTH]" (x, y or z; WIDTH in bead diameters, in
// (0, 1000]; without it the width stays) or "off"; what is wrong with it
// otherwise (the section then unchanged), for the caller to report.
std::string parse_section(const std::string& text, Section& s);
// "y:1.5", or "off" for the whole specimen.
std::string section_text(const Section& s);

// The force chains' colour map and colour range (N): from the threshold,
// chain_threshold x F_mean, to the largest force (never below the
// threshold). The renderer and the legends use these two.
inline constexpr plot::ColorMap kChainMap = plot::ColorMap::Glow;
struct ForceRange {
  float min = 0, max = 0;
};
ForceRange chain_force_range(const ViewSettings& s, const FrameGeometry& g);

// Owns GL buffers for FrameGeometry and fills them from host arrays (tests,
// the host-copy path). Sizes grow, never shrink.
class GeometryBuffers {
 public:
  explicit GeometryBuffers(const Gl& gl);
  ~GeometryBuffers();
  GeometryBuffers(const GeometryBuffers&) = delete;
  GeometryBuffers& operator=(const GeometryBuffers&) = delete;

  // Makes room for `beads` beads and `segments` segments (GL_STREAM_DRAW).
  void reserve(std::size_t beads, std::size_t segments);
  // Also sets the geometry's bead_radius (their mean radius).
  void upload_beads(const std::vector<float>& xyzr, const std::vector<float>& values);
  // segments: 8 floats per contact (FrameGeometry); forces in N.
  void upload_segments(const std::vector<float>& segments, float mean_force, float max_force);
  GLuint beads() const { return beads_; }
  GLuint values() const { return values_; }
  GLuint segments() const { return segments_; }
  std::size_t bead_capacity() const { return bead_cap_; }
  std::size_t segment_capacity() const { return seg_cap_; }
  // The geometry to draw (walls and bounds filled by the caller).
  FrameGeometry geometry() const { return geom_; }
  FrameGeometry& mutable_geometry() { return geom_; }

 private:
  const Gl& gl_;
  GLuint beads_ = 0, values_ = 0, segments_ = 0;
  std::size_t bead_cap_ = 0, seg_cap_ = 0;
  FrameGeometry geom_;
};

// Colour buffer `buffer` of `fbo` (RGBA8), top row first: attachment 0 of
// the renderer's framebuffers, or GL_BACK of a window (fbo 0).
plot::Image read_framebuffer(const Gl& gl, GLuint fbo, int width, int height,
                             GLenum buffer = GL_COLOR_ATTACHMENT0);

class Renderer {
 public:
  explicit Renderer(const Gl& gl);  // compiles the shaders; throws RenderError
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Sets the frame size (1..16384 per side; RenderError otherwise).
  void resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }

  void draw(const Camera& camera, const FrameGeometry& geometry, const ViewSettings& settings);
  void draw(const ViewProjection& vp, const FrameGeometry& geometry, const ViewSettings& settings);
  // The last frame, top row first.
  plot::Image read_pixels() const;
  GLuint framebuffer() const { return scene_fbo_; }
  GLuint color_texture() const { return color_tex_; }

  static constexpr int kMaxSize = 16384;

 private:
  void draw_opaque(const FrameGeometry& g, const ViewSettings& s);
  void draw_transparent(const FrameGeometry& g, const ViewSettings& s);
  void draw_walls(ShaderProgram& p, const std::vector<WallQuad>& walls, const ViewSettings& s);
  void draw_walls_blended(const FrameGeometry& g, const ViewSettings& s);
  void composite();
  void draw_segments(GLuint buffer, std::size_t count);
  void draw_beads(ShaderProgram& p, const FrameGeometry& g, const ViewSettings& s, float alpha);
  void set_common(ShaderProgram& p, const ViewSettings& s, bool force_map);
  // section_ and section_offset_ from the settings and what is drawn
  void set_section(const FrameGeometry& g, const ViewSettings& s);
  void bind_colormap(ShaderProgram& p, plot::ColorMap map);
  void release_targets();

  const Gl& gl_;
  std::unique_ptr<ShaderProgram> sphere_, sphere_oit_, segment_, wall_, wall_oit_, composite_;
  GLuint vao_ = 0, empty_vao_ = 0, edge_buffer_ = 0;
  struct MapTexture {
    GLuint tex = 0;
    int size = 0;
  };
  std::map<plot::ColorMap, MapTexture> maps_;
  int width_ = 0, height_ = 0;
  GLuint scene_fbo_ = 0, color_tex_ = 0, depth_rb_ = 0;
  GLuint oit_fbo_ = 0, accum_tex_ = 0, weight_tex_ = 0;
  // per frame
  glm::mat4 view_{1}, proj_{1};
  bool ortho_ = false;
  glm::vec2 depth_range_{0, 1};
  glm::vec4 section_{0, 0, 0, 0};  // unit normal, half-width (m; 0: no section)
  float section_offset_ = 0;       // the plane's offset along the normal (m)
};

}  // namespace simsols::render
