// Frames: offscreen pictures of a simulation, for `simsols snapshot` and
// `simsols run --frames DIR --every N`.
//
// FrameOptions are the flags both commands share (view, size, colouring,
// mode, force chains, legend, GL backend); resolve() fills in the scene's
// [view] hints for flags not given, checks them and reports a bad value
// with the flag's name (or the scene file and field) and what is allowed. A
// FrameExporter owns a headless GL context (EGL surfaceless, else OSMesa)
// and the renderer; it must exist before the simulation is created, so the
// OpenCL device can share the GL context where it offers cl_khr_gl_sharing
// (it installs that device as the process default). Frames are written
// atomically (name.tmp, then rename): a failed or interrupted export leaves
// no half-written PNG.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/gl/camera.h"
#include "render/gl/gl_context.h"
#include "render/plot/image.h"
#include "render/gl/renderer.h"

namespace simsols::render {
class AlioscopyOutput;
struct DisplayProfile;
}
#include "render/view/view_pack.h"

namespace simsols {

class Simulation;
struct Scene;

struct FrameFlags {
  std::string view = "three-quarter";
  std::string size = "1280x720";
  std::string color_by;  // empty: the scene's default (default_color_field, view_pack.h)
  std::string mode = "opaque";
  bool chains = false;
  double threshold = 1.0;
  std::string range;  // "MIN:MAX", empty = the field's current range
  bool no_legend = false;
  bool no_walls = false;
  std::string section;  // "AXIS[:WIDTH]": a slab through the middle (render::Section)
  std::string gl = "auto";
  std::string stereo;   // "alioscopy": the 8-view interleaved image and the views
  std::string display;  // display profile: a file or a built-in name (display_profile)
  // The registered options, to tell a flag given on the command line from
  // its default (set by add_frame_flags).
  std::map<std::string, const CLI::Option*> options;
  bool given(const std::string& flag) const;
};

// Registers the flags on a subcommand.
void add_frame_flags(CLI::App* cmd, FrameFlags& flags);

struct FrameOptions {
  render::ViewPreset view = render::ViewPreset::ThreeQuarter;
  int width = 1280, height = 720;
  ColorField field = ColorField::Layer;
  render::ViewSettings settings;
  std::optional<std::pair<double, double>> range;
  bool legend = true;
  render::GlBackend backend = render::GlBackend::Auto;
  bool alioscopy = false;
  std::string display_path;  // --display (alioscopy); empty = the built-in Alioscopy HD

  // The flags, with the scene's [view] hints for those not given on the
  // command line; no colouring given either way: grain for a scene with
  // clumps, else layer (also without a scene). Throws SceneError naming
  // the flag (or the scene file and its view.* field) and the allowed values.
  static FrameOptions resolve(const FrameFlags& flags, const Scene* scene = nullptr);
};

// The display profile --display names: a file, else the built-in profile
// named by its file name ("alioscopy_hd", or assets/displays/alioscopy_hd.toml
// from any directory); empty = the built-in Alioscopy HD. Throws SceneError
// listing every problem of the profile, or "did you mean" for a bad name.
render::DisplayProfile display_profile(const std::string& given);

// Parses "WxH" (each side 1..16384); throws SceneError naming `flag`.
std::pair<int, int> parse_frame_size(const std::string& text, const std::string& flag);

class FrameExporter {
 public:
  // Opens a headless GL context and an OpenCL device (`engine`) sharing it
  // where the device can: the simulations it draws run on device().
  FrameExporter(const FrameOptions& options, const EngineOptions& engine);
  ~FrameExporter();
  const std::shared_ptr<Device>& device() const { return device_; }

  // Starts drawing `sim` (fits the camera to the specimen and its box),
  // with the options resolved again against its scene's [view] hints.
  void attach(Simulation& sim, const FrameFlags& flags);
  // The reference for the displacement fields: the current positions; the
  // camera is fitted again to the specimen and its box as they are now.
  void set_reference();
  // The caption of the next frames (with the legend: not under
  // --no-legend): the test's title and its state, to which the step and
  // the simulated time are added. A scale bar comes with it.
  void set_caption(std::string title, std::string state);
  render::Camera& camera() { return camera_; }

  plot::Image render();
  // Renders and writes a PNG atomically. Throws RenderError naming the path.
  // With --stereo alioscopy: `path` is the interleaved image at the display's
  // resolution, and STEM_view0..7.png and STEM_grid.png are written beside it.
  void write(const std::string& path);
  // The files write() produces for `path`.
  std::vector<std::string> outputs(const std::string& path) const;
  // "EGL surfaceless: llvmpipe ...; buffers: host copy (...)"
  std::string describe() const;

 private:
  void fit_camera();  // to the attached view's bounds, at the frame's aspect
  void write_alioscopy(const std::string& path);
  // The caption and the scale bar; returns the caption's rectangle.
  plot::Rect annotate(plot::Image& img) const;
  // Packs the current state for drawing; the settings with the colour range.
  render::ViewSettings update_view();

  FrameOptions opt_;
  std::unique_ptr<render::GlContext> context_;
  std::shared_ptr<Device> device_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::AlioscopyOutput> alioscopy_;
  struct Attached;
  std::unique_ptr<Attached> sim_;
  render::Camera camera_;
  std::string title_, state_;
};

}  // namespace simsols
