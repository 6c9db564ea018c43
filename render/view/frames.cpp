#include "render/view/frames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "render/gl/alioscopy.h"
#include "render/plot/colormap.h"
#include "render/plot/font.h"
#include "solver/common/did_you_mean.h"
#include "solver/common/errors.h"
#include "render/plot/png.h"
#include "render/view/frame_caption.h"
#include "render/view/sim_view.h"
#include "solver/core/simulation.h"

namespace simsols {

namespace {

SceneError flag_error(const std::string& flag, const std::string& what) {
  return SceneError("bad_flag", "command line", 0, flag, what);
}

}  // namespace

bool FrameFlags::given(const std::string& flag) const {
  auto it = options.find(flag);
  return it != options.end() && it->second && it->second->count() > 0;
}

void add_frame_flags(CLI::App* cmd, FrameFlags& f) {
  f.options["--view"] =
      cmd->add_option("--view", f.view, "Camera preset: front, side, top, three-quarter")
          ->capture_default_str();
  f.options["--size"] =
      cmd->add_option("--size", f.size, "Frame size WxH in pixels (each side 1..16384)")
          ->capture_default_str();
  f.options["--color-by"] =
      cmd->add_option("--color-by", f.color_by,
                      "Bead colour: " + color_field_names() +
                          " (default: grain for scenes with clumps, else layer)");
  f.options["--mode"] =
      cmd->add_option("--mode", f.mode, "opaque, transparent (see inside) or chains (force chains)")
          ->capture_default_str();
  f.options["--chains"] = cmd->add_flag("--chains", f.chains, "Draw the force chains over any mode");
  f.options["--threshold"] =
      cmd->add_option("--threshold", f.threshold,
                      "Force chains: hide contacts with F/F_mean below this (>= 0)")
          ->capture_default_str();
  cmd->add_option("--range", f.range, "Colour range MIN:MAX (default: the field's range)");
  cmd->add_flag("--no-legend", f.no_legend, "No colour legend");
  cmd->add_flag("--no-walls", f.no_walls, "Do not draw the walls");
  cmd->add_option("--section", f.section,
                  "Draw a slab through the middle only: AXIS[:WIDTH], the axis normal to it "
                  "(x, y, z) and its width in mean bead diameters (default 2), e.g. y:1.5");
  cmd->add_option("--gl", f.gl, "Headless OpenGL: auto, egl, osmesa")->capture_default_str();
  cmd->add_option("--stereo", f.stereo,
                  "alioscopy: the 8-view interleaved image for the display, and its views");
  cmd->add_option("--display", f.display,
                  "Display profile for --stereo: a .toml file, or a built-in profile by name "
                  "(alioscopy_hd, the default)");
}

namespace {

// What is wrong with a "WxH" size, or empty (w and h then set).
std::string size_problem(const std::string& text, int& w, int& h) {
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    return "'" + text + "' is not WIDTHxHEIGHT (e.g. 1920x1080)";
  if (w < 1 || h < 1 || w > render::Renderer::kMaxSize || h > render::Renderer::kMaxSize)
    return "'" + text + "': each side must be in [1, " +
           std::to_string(render::Renderer::kMaxSize) + "] pixels";
  return {};
}

}  // namespace

std::pair<int, int> parse_frame_size(const std::string& text, const std::string& flag) {
  int w = 0, h = 0;
  if (const std::string p = size_problem(text, w, h); !p.empty()) throw flag_error(flag, p);
  return {w, h};
}

FrameOptions FrameOptions::resolve(const FrameFlags& flags, const Scene* scene) {
  // Scene hints fill in the flags not given; an error then names the scene
  // file and its view.* field.
  FrameFlags f = flags;
  std::map<std::string, std::string> from_scene;  // flag -> scene field
  if (scene) {
    const ViewHints& v = scene->view;
    auto take = [&](const char* flag, const char* key, auto& dst, const auto& hint, bool has) {
      if (!has || flags.given(flag)) return;
      dst = hint;
      from_scene[flag] = std::string("view.") + key;
    };
    take("--view", "view", f.view, v.view, !v.view.empty());
    take("--color-by", "color_by", f.color_by, v.color_by, !v.color_by.empty());
    take("--mode", "mode", f.mode, v.mode, !v.mode.empty());
    take("--size", "size", f.size, v.size, !v.size.empty());
    take("--chains", "chains", f.chains, v.chains.value_or(false), v.chains.has_value());
    take("--threshold", "threshold", f.threshold, v.threshold.value_or(0), v.threshold.has_value());
  }
  auto flag_error = [&](const std::string& flag, const std::string& what) {
    if (auto it = from_scene.find(flag); it != from_scene.end())
      return SceneError("bad_value", scene->source_path, 0, it->second, what);
    return SceneError("bad_flag", "command line", 0, flag, what);
  };
  FrameOptions o;
  if (auto v = render::parse_view_preset(f.view)) o.view = *v;
  else throw flag_error("--view", "'" + f.view + "' is not one of: front, side, top, three-quarter");
  if (const std::string p = size_problem(f.size, o.width, o.height); !p.empty())
    throw flag_error("--size", p);
  if (f.color_by.empty()) o.field = scene ? default_color_field(*scene) : ColorField::Layer;
  else if (auto c = parse_color_field(f.color_by)) o.field = *c;
  else throw flag_error("--color-by", "'" + f.color_by + "' is not one of: " + color_field_names());
  if (auto m = render::parse_view_mode(f.mode)) o.settings.mode = *m;
  else throw flag_error("--mode", "'" + f.mode + "' is not one of: opaque, transparent, chains");
  o.settings.show_chains = f.chains;
  if (!(f.threshold >= 0) || !std::isfinite(f.threshold))
    throw flag_error("--threshold", "must be a finite ratio >= 0 (F/F_mean)");
  o.settings.chain_threshold = float(f.threshold);
  if (!f.range.empty()) {
    double lo = 0, hi = 0;
    char c = 0, extra = 0;
    if (std::sscanf(f.range.c_str(), "%lf%c%lf%c", &lo, &c, &hi, &extra) != 3 || c != ':' ||
        !std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
      throw flag_error("--range", "'" + f.range + "' is not MIN:MAX with MIN < MAX");
    o.range = {lo, hi};
  }
  o.legend = !f.no_legend;
  o.settings.show_walls = !f.no_walls;
  if (!f.section.empty()) {
    if (const std::string p = render::parse_section(f.section, o.settings.section); !p.empty())
      throw flag_error("--section", p);
  }
  if (auto b = render::parse_gl_backend(f.gl)) o.backend = *b;
  else throw flag_error("--gl", "'" + f.gl + "' is not one of: auto, egl, osmesa");
  o.settings.bead_map = render::colormap_for(o.field);
  if (!f.stereo.empty() && f.stereo != "alioscopy")
    throw flag_error("--stereo", "'" + f.stereo + "' is not one of: alioscopy");
  o.alioscopy = f.stereo == "alioscopy";
  if (!f.display.empty() && !o.alioscopy)
    throw flag_error("--display", "a display profile goes with --stereo alioscopy");
  if (o.alioscopy) {
    o.display_path = f.display;
    const render::DisplayProfile p = display_profile(o.display_path);
    o.width = p.width;
    o.height = p.height;
  }
  return o;
}

render::DisplayProfile display_profile(const std::string& given) {
  // No --display: the built-in defaults, which are those of
  // assets/displays/alioscopy_hd.toml (a test keeps them equal).
  if (given.empty()) return {};
  const std::string name = std::filesystem::path(given).stem().string();
  try {
    if (std::filesystem::exists(given)) return render::load_display_profile(given);
    if (auto text = render::builtin_display_profile(name))
      return render::parse_display_profile(*text, "built-in " + name + ".toml");
  } catch (const render::DisplayProfileError& e) {
    throw SceneError(e.file, e.problems);
  }
  const std::vector<std::string> names = render::builtin_display_profiles();
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  throw SceneError("io", given, 0, "--display",
                   "no such file, and '" + name + "' is not a built-in display profile" +
                       did_you_mean(name, names) + "; built-in profiles: " + list);
}

struct FrameExporter::Attached {
  Simulation* sim = nullptr;
  std::unique_ptr<render::SimulationView> view;
};

FrameExporter::FrameExporter(const FrameOptions& options, const EngineOptions& engine)
    : opt_(options) {
  context_ = render::create_headless_context(opt_.backend);
  renderer_ = std::make_unique<render::Renderer>(context_->gl());
  renderer_->resize(opt_.width, opt_.height);
  // The OpenCL device shares this GL context where it can.
  device_ = Device::open(engine, render::cl_share_properties(context_->share_handles()));
}

FrameExporter::~FrameExporter() = default;

void FrameExporter::attach(Simulation& sim, const FrameFlags& flags) {
  const render::GlBackend backend = opt_.backend;
  opt_ = FrameOptions::resolve(flags, &sim.scene());
  opt_.backend = backend;
  renderer_->resize(opt_.width, opt_.height);
  sim_ = std::make_unique<Attached>();
  sim_->sim = &sim;
  sim_->view = std::make_unique<render::SimulationView>(context_->gl(), sim);
  camera_.set_preset(opt_.view);
  fit_camera();
}

void FrameExporter::fit_camera() {
  camera_.fit(sim_->view->lo(), sim_->view->hi(), double(opt_.width) / opt_.height);
}

void FrameExporter::set_reference() {
  if (!sim_) return;
  sim_->view->packer().set_reference();
  // the specimen as it is now (a pour rains from three times its height):
  // the camera frames it again, as the lab does when a stage ends
  sim_->view->refit_bounds();
  fit_camera();
}

void FrameExporter::set_caption(std::string title, std::string state) {
  title_ = std::move(title);
  state_ = std::move(state);
}

plot::Rect FrameExporter::annotate(plot::Image& img) const {
  char when[96];
  std::snprintf(when, sizeof when, "step %lld · t = %.4g s", static_cast<long long>(sim_->sim->steps()),
                sim_->sim->time());
  const plot::Rect caption =
      render::draw_caption(img, {title_, state_.empty() ? std::string(when) : state_ + " · " + when});
  render::draw_scale_bar(img, camera_);
  return caption;
}

std::string FrameExporter::describe() const {
  std::string s = context_->description();
  if (sim_) s += "; particle buffers: " + sim_->view->bridge().path();
  return s;
}

namespace {

// The force chains' key: the colour bar in newtons from the threshold to the
// largest force, what is drawn, and how wall contacts look.
plot::Legend chain_legend(const render::ViewSettings& s, const render::FrameGeometry& g) {
  plot::Legend legend;
  legend.title = "normal force (N)";
  legend.map = render::kChainMap;
  const render::ForceRange range = render::chain_force_range(s, g);
  legend.min = range.min;
  legend.max = range.max;
  char line[160];
  std::snprintf(line, sizeof line, "drawn: F \u2265 %.3g \u00d7 mean (%.3g N)\nwidth grows with force; grey: wall contacts",
                double(s.chain_threshold), legend.min);
  legend.note = line;
  legend.dark = true;
  return legend;
}

}  // namespace

plot::Image FrameExporter::render() {
  if (!sim_) throw render::RenderError("FrameExporter::render before attach()");
  const render::ViewSettings s = update_view();
  const render::FrameGeometry g = sim_->view->geometry();
  renderer_->draw(camera_, g, s);
  plot::Image img = renderer_->read_pixels();
  if (!opt_.legend) return img;
  const plot::Rect caption = annotate(img);
  if (s.mode == render::ViewMode::Chains) {  // the beads are ghosts: the chains' key only
    plot::draw_legend(img, chain_legend(s, g));
    return img;
  }
  plot::Legend legend;
  legend.title = render::legend_title(opt_.field);
  legend.note = render::legend_note(opt_.field);
  legend.map = s.bead_map;
  legend.min = s.value_min;
  legend.max = s.value_max;
  legend.dark = true;
  // a narrow frame: the legend moves to the bottom right rather than cover
  // the caption (unless the chains' key is there)
  const plot::Rect panel = plot::legend_layout(img.width, img.height, legend).panel;
  const bool covers = panel.x0 < caption.x1 && caption.x0 < panel.x1 && panel.y0 < caption.y1 &&
                      caption.y0 < panel.y1;
  if (covers && !s.chains_visible()) legend.corner = plot::Legend::Corner::BottomRight;
  plot::draw_legend(img, legend);
  if (s.chains_visible()) {
    plot::Legend chains = chain_legend(s, g);
    chains.corner = plot::Legend::Corner::BottomRight;
    plot::draw_legend(img, chains);
  }
  return img;
}

render::ViewSettings FrameExporter::update_view() {
  const auto update = sim_->view->update(opt_.field, opt_.settings.chains_visible());
  render::ViewSettings s = opt_.settings;
  s.value_min = float(opt_.range ? opt_.range->first : update.range.min);
  s.value_max = float(opt_.range ? opt_.range->second : update.range.max);
  return s;
}

std::vector<std::string> FrameExporter::outputs(const std::string& path) const {
  std::vector<std::string> files{path};
  if (!opt_.alioscopy) return files;
  const std::filesystem::path p(path);
  const std::string stem = (p.parent_path() / p.stem()).string();
  for (int k = 0; k < render::kAlioscopyViews; ++k)
    files.push_back(stem + "_view" + std::to_string(k) + ".png");
  files.push_back(stem + "_grid.png");
  return files;
}

namespace {

// "view k" in the top left corner of each view of a grid image.
void label_views(plot::Image& img, const render::GridLayout& grid) {
  const double aspect = double(img.width) / img.height;
  for (int k = 0; k < render::kAlioscopyViews; ++k) {
    const plot::Rect c = grid.cell(k, img.width, img.height, aspect);
    const double size = std::max(11.0, 0.06 * (c.y1 - c.y0));
    plot::draw_text(img, c.x0 + 0.5 * size, c.y0 + 1.4 * size, "view " + std::to_string(k), size,
                    {236, 238, 242});
  }
}

}  // namespace

void FrameExporter::write_alioscopy(const std::string& path) {
  const render::DisplayProfile profile = display_profile(opt_.display_path);
  if (!alioscopy_) alioscopy_ = std::make_unique<render::AlioscopyOutput>(context_->gl(), profile);
  const render::ViewSettings s = update_view();
  render::StereoRig rig;
  alioscopy_->render_views(*renderer_, rig, camera_, sim_->view->geometry(), s);
  const std::vector<std::string> files = outputs(path);
  try {
    alioscopy_->compose(render::AlioscopyOutput::Mode::Interleaved);
    plot::write_png(alioscopy_->read_pixels(), files[0]);
    for (int k = 0; k < render::kAlioscopyViews; ++k)
      plot::write_png(alioscopy_->read_view(k), files[1 + k]);
    alioscopy_->compose(render::AlioscopyOutput::Mode::Grid);
    plot::Image grid = alioscopy_->read_pixels();
    label_views(grid, alioscopy_->grid());
    plot::write_png(grid, files[9]);
  } catch (const IoError& e) {
    throw IoError(std::string("cannot write the frame: ") + e.what());
  }
  renderer_->resize(opt_.width, opt_.height);
}

void FrameExporter::write(const std::string& path) {
  if (opt_.alioscopy) return write_alioscopy(path);
  const plot::Image img = render();
  try {
    plot::write_png(img, path);
  } catch (const IoError& e) {
    throw IoError(std::string("cannot write the frame: ") + e.what());
  }
}

}  // namespace simsols
