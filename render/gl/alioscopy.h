// Alioscopy: eight views interleaved at subpixel level for a lenticular
// autostereoscopic screen, and the views shown flat for people without one.
//
// The mapping (docs/alioscopy.md). For the output subpixel in physical
// screen pixel column X (from the left), row Y (from the top), channel
// c = 0, 1, 2 (R, G, B):
//   v = (Y - (3X + c) + phase) mod 8     (flip_slant: (-Y - (3X + c) + phase) mod 8)
//   view = v, or 7 - v when reversed
// The period is 8 subpixels and the pattern shifts one subpixel per row.
// Every channel samples its view at the same pixel-centre coordinate. X and
// Y are physical screen pixels: the window's position on the screen is
// added, so the pattern stays fixed to the lenses when the window moves.
// This matches Alioscopy's sample shader, which counts rows from the bottom
// and adds the window offset. The pass writes the output 1:1 into an RGBA8
// target; nothing filters or scales the image afterwards.
//
// The display profile (assets/displays/*.toml, also built in) holds the panel size, the
// phase, the reversed-order and flipped-slant switches (public descriptions
// disagree on both), the per-view resolution and the rig's spacing ratio.
//
// AlioscopyOutput owns the views (a 2D texture array, one layer per view),
// renders them with a Renderer and a StereoRig, and composes:
//   Interleaved  the image for the screen
//   Grid         the eight views in the grid that shows them largest
//                (grid_layout: 3 x 3 for views of the output's aspect, the
//                ninth cell empty), view 0 top left, left to right
//   Single       one view, full size
// deinterleave() is the lens simulation: what the eye behind the lenses
// would get of view k from an interleaved image.
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl/camera.h"
#include "render/gl/gl_api.h"
#include "render/plot/image.h"
#include "solver/common/problems.h"
#include "render/gl/renderer.h"
#include "render/gl/stereo_rig.h"

namespace simsols::render {

class ShaderProgram;

// The number of views: fixed by the interleaving formula (period 8
// subpixels); everything that loops over the views counts to this.
inline constexpr int kAlioscopyViews = 8;

struct DisplayProfile {
  std::string name = "Alioscopy HD (1920x1080, 8 views)";
  int width = 1920, height = 1080;  // physical pixels of the panel
  int views = kAlioscopyViews;      // fixed by the interleaving formula
  int phase = 0;                    // [0, 7]
  bool reversed = false;
  bool flip_slant = false;
  double view_scale = 0.375;        // per-view resolution / output, (0, 1]
  double interaxial_ratio = 6.5 / 400;  // camera spacing / focus when interaxial = 0
  double interaxial = 0;            // m between neighbouring cameras; 0 = ratio x focus
  double focus = 0;                 // m to the focus plane; 0 = the camera's distance to its target
  bool nearest_views = false;       // sample the views without filtering (tests)

  // The views' size for an output of that size: ceil(side x view_scale).
  glm::ivec2 view_size(int output_width, int output_height) const;
  // `rig` with this display's settings where it leaves them to the display
  // (interaxial, focus, ratio at 0), and the display's view count.
  StereoRig rig(const StereoRig& rig) const;
  int view_width() const { return view_size(width, height).x; }  // at the panel's size
  int view_height() const { return view_size(width, height).y; }
};

// A display profile that cannot be used: every problem found in one pass
// (unknown keys, with a "did you mean", and values out of range), each
// naming the field and what is allowed; what() names the file once.
struct DisplayProfileError : std::runtime_error {
  DisplayProfileError(std::string file, std::vector<FileProblem> problems);
  std::string file;
  std::vector<FileProblem> problems;
};

// Reads a profile file (display_profile.cpp); throws DisplayProfileError.
DisplayProfile load_display_profile(const std::string& path);
// The same from text; `name` names it in messages.
DisplayProfile parse_display_profile(std::string_view text, const std::string& name);
// The profiles of assets/displays, embedded at build time: their names
// ("alioscopy_hd"), and the text of one (nullopt for another name).
std::vector<std::string> builtin_display_profiles();
std::optional<std::string_view> builtin_display_profile(std::string_view name);

// The view index of subpixel (X, Y, c) (screen pixels, Y from the top).
int alioscopy_view(int x, int y, int c, const DisplayProfile& profile);

// Lens simulation: view k as seen through the lenses. Pixel (x, y), channel
// c is taken from the nearest subpixel of the same channel in the same row
// that shows view k (those lie every 8 pixels); `window` is the image's
// top-left pixel on the screen.
plot::Image deinterleave(const plot::Image& interleaved, int k, const DisplayProfile& profile,
                         glm::ivec2 window = {0, 0});

// The grid of the Grid mode for an output of width x height and views of
// `aspect` (width / height): the columns and rows (columns x rows >= 8,
// as few rows as that many columns allow) that show each view largest
// when fitted in its cell with its aspect kept.
struct GridLayout {
  int columns = 4, rows = 2;
  // Where view k is shown, in output pixels from the top left (x0, y0
  // inclusive, x1, y1 exclusive); for labels drawn over the grid.
  plot::Rect cell(int k, int width, int height, double aspect) const;
};
GridLayout grid_layout(int width, int height, double aspect);

class AlioscopyOutput {
 public:
  enum class Mode { Interleaved, Grid, Single };

  AlioscopyOutput(const Gl& gl, const DisplayProfile& profile);
  ~AlioscopyOutput();
  AlioscopyOutput(const AlioscopyOutput&) = delete;
  AlioscopyOutput& operator=(const AlioscopyOutput&) = delete;

  const DisplayProfile& profile() const { return profile_; }
  // Output size (defaults to the panel); the views follow it
  // (DisplayProfile::view_size).
  void resize_output(int width, int height);
  int output_width() const { return out_w_; }
  int output_height() const { return out_h_; }
  int view_width() const { return view_.x; }
  int view_height() const { return view_.y; }

  // Renders the eight views of `camera`.
  void render_views(Renderer& renderer, const StereoRig& rig, const Camera& camera,
                    const FrameGeometry& geometry, const ViewSettings& settings);
  // Copies the current frame of `renderer` into view k (tests fill views
  // with known images this way).
  void copy_view(int k, const Renderer& renderer);
  // Fills view k with one colour, or with an image of the views' size
  // (row 0 at the top) (tests, imported views).
  void fill_view(int k, glm::vec4 rgba);
  void upload_view(int k, const plot::Image& image);

  // Composes into the output framebuffer. `window` is the output's
  // top-left pixel on the physical screen (Interleaved only).
  void compose(Mode mode, int single_view = 0, glm::ivec2 window = {0, 0});
  // The same straight into another framebuffer (a window's: no copy), the
  // output's size with its bottom-left corner at `at` (GL pixels).
  void compose_into(GLuint framebuffer, glm::ivec2 at, Mode mode, int single_view = 0,
                    glm::ivec2 window = {0, 0});
  // The Grid mode's layout for the current output (views of its aspect).
  GridLayout grid() const;
  plot::Image read_pixels() const;
  plot::Image read_view(int k) const;
  GLuint framebuffer() const { return out_fbo_; }
  GLuint views_texture() const { return views_tex_; }

 private:
  const Gl& gl_;
  DisplayProfile profile_;
  std::unique_ptr<ShaderProgram> program_;
  GLuint views_tex_ = 0, layer_fbo_ = 0, out_tex_ = 0, out_fbo_ = 0, vao_ = 0;
  int out_w_ = 0, out_h_ = 0;
  glm::ivec2 view_{1, 1};
};

}  // namespace simsols::render
