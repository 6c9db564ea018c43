#include "app/lab/lab_app.h"

#define GLFW_INCLUDE_NONE  // GL comes from render/gl/gl_api.h
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <atomic>
#include <chrono>
#include <future>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "solver/core/engine_options.h"
#include "solver/common/errors.h"
#include "app/lab/lab_script.h"
#include "render/view/particle_bridge.h"
#include "render/plot/font.h"
#include "render/plot/png.h"
#include "render/view/view_pack.h"

namespace simsols {

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}
constexpr float kPanelWidth = 430;  // pixels at scale 1
constexpr float kFontSize = 14;     // pixels: the em of the lab's text

// The lab's text is DejaVu Sans, the face of the charts (render/plot/font.h):
// ImGui's built-in font has no Greek letters. The atlas holds Latin-1,
// Greek, general punctuation (′ – —), super- and subscripts (⁻ ₃) and the
// minus and comparison signs, so labels can read τ/σ, σ′v, φ, ε_v, σ₃.
void load_lab_font() {
  static const ImWchar kRanges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2000, 0x206F, 0x2070,
                                    0x209F, 0x2212, 0x2212, 0x2264, 0x2265, 0};
  ImGuiIO& io = ImGui::GetIO();
  std::string problem;
  try {
    const std::string path = plot::text_font_file();
    if (io.Fonts->AddFontFromFileTTF(path.c_str(), kFontSize, nullptr, kRanges)) return;
    problem = "Dear ImGui could not read the font " + path;
  } catch (const std::runtime_error& e) {
    problem = e.what();
  }
  std::fprintf(stderr,
               "simsols lab: %s; using ImGui's built-in font, which shows no Greek letters\n",
               problem.c_str());
  io.Fonts->AddFontDefault();
}
}  // namespace

LabApp::LabApp(const LabOptions& options) : opt_(options) {
  window_ = std::make_unique<LabWindow>(opt_.width, opt_.height, "SimSols — virtual geotechnical lab");
  glfwSetWindowUserPointer(window_->handle(), this);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
  ImGui::StyleColorsDark();
  load_lab_font();
  ImGui_ImplGlfw_InitForOpenGL(window_->handle(), true);
  ImGui_ImplOpenGL3_Init("#version 330");
  // The OpenCL device shares the window's GL context where it can.
  device_ = Device::open(engine_options_from_environment(),
                         render::cl_share_properties(window_->share_handles()));
  renderer_ = std::make_unique<render::Renderer>(window_->gl());
  exp_ = std::make_unique<LabExperiment>(device_);
  exp_->set_precision(Precision::Float);
  std::string err = opt_.scene.empty() ? exp_->load_preset(6.35, 160) : exp_->load_scene_file(opt_.scene);
  if (!err.empty()) {
    message_ = err;
    if (!opt_.scene.empty()) err = exp_->load_preset(6.35, 160);
  }
  if (const int bench = lab_bench_index(exp_->scene()); bench >= 0) apparatus_ = bench;
  if (opt_.script.empty()) {
    act(exp_->prepare());
    return;
  }
  std::ifstream in(opt_.script);
  if (!in) throw SceneError("io", opt_.script, 0, "--script", "cannot read the script");
  script_ = std::make_unique<Script>(*this);
  script_->file = opt_.script;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    line = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
    script_->lines.emplace_back(n, line);
  }
}

LabApp::~LabApp() {
  sim_view_.reset();
  alioscopy_.reset();
  renderer_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void LabApp::act(const std::string& error) {
  if (!error.empty()) message_ = error;
}

void LabApp::attach_view() {
  if (!exp_->simulation() || exp_->generation() == generation_) return;
  generation_ = exp_->generation();
  if (!field_chosen) field = default_color_field(exp_->simulation()->scene());
  sim_view_ = std::make_unique<render::SimulationView>(window_->gl(), *exp_->simulation());
  fit_view();
}

// The camera on the beads and walls where they are now (F, the panel's
// Fit, a new simulation, the end of a stage: refit_on_stage).
void LabApp::fit_view() {
  if (!sim_view_) return;
  sim_view_->refit_bounds();
  camera_.set_preset(preset_);
  camera_.fit(sim_view_->lo(), sim_view_->hi(), double(view_w_) / std::max(1, view_h_));
}

// A specimen settles into a fraction of the height it was poured in: the
// view is framed again once it is prepared, loaded and when the test starts.
void LabApp::refit_on_stage() {
  const LabStage st = exp_->stage();
  if (st == fitted_stage_) return;
  fitted_stage_ = st;
  if (st == LabStage::Prepared || st == LabStage::Loaded || st == LabStage::Running) fit_view();
}

void LabApp::poll_input() {
  ImGuiIO& io = ImGui::GetIO();
  GLFWwindow* w = window_->handle();
  if (!io.WantCaptureKeyboard) {
    // ImGui 1.86 (Debian 12) indexes keys by the platform's (GLFW's) codes
    auto pressed = [&](int key) { return ImGui::IsKeyPressed(key, false); };
    if (pressed(GLFW_KEY_SPACE)) exp_->paused() ? exp_->resume() : exp_->pause();
    if (pressed(GLFW_KEY_S)) act(exp_->step());
    if (pressed(GLFW_KEY_R)) act(exp_->reset());
    if (pressed(GLFW_KEY_F)) fit_view();
    if (pressed(GLFW_KEY_F11)) window_->toggle_fullscreen();
    if (pressed(GLFW_KEY_H) || pressed(GLFW_KEY_F1)) help_ = !help_;
    if (pressed(GLFW_KEY_ESCAPE)) help_ = false;
  }
  // Mouse in the viewport: left drag orbits, right drag pans, wheel zooms.
  double mx = 0, my = 0;
  glfwGetCursorPos(w, &mx, &my);
  if (!io.WantCaptureMouse) {
    for (int b : {0, 1})
      if (ImGui::IsMouseClicked(b)) dragging_ = b;
    if (io.MouseWheel != 0) camera_.zoom(std::pow(0.9, io.MouseWheel));
  }
  if (dragging_ >= 0 && !ImGui::IsMouseDown(dragging_)) dragging_ = -1;
  if (dragging_ == 0) camera_.orbit(-(mx - last_x_) * 0.3, (my - last_y_) * 0.3);
  if (dragging_ == 1) camera_.pan((mx - last_x_) / view_h_, -(my - last_y_) / view_h_);
  last_x_ = mx;
  last_y_ = my;
}

render::ViewSettings LabApp::pack_view() {
  // contacts are packed every frame (0.5 ms for 5 000 beads): the status
  // line counts them, the chains draw them when asked
  const auto update = sim_view_->update(field, true);
  contacts_ = update.contacts.total;
  // the stereo views show the look of the last flat view chosen
  if (view == LabView::Opaque || view == LabView::Transparent || view == LabView::Chains) look_ = view;
  render::ViewSettings s;
  s.mode = look_ == LabView::Opaque   ? render::ViewMode::Opaque
           : look_ == LabView::Chains ? render::ViewMode::Chains
                                      : render::ViewMode::Transparent;
  s.show_chains = look_ == LabView::Chains || view == LabView::Chains || chains_overlay;
  s.chain_threshold = threshold;
  s.section = section;
  s.bead_map = render::colormap_for(field);
  s.value_min = update.range.min;
  s.value_max = update.range.max;
  // the walls where they are now: read here, with the solver idle, so the
  // drawing itself touches nothing of the solver's
  geometry_ = sim_view_->geometry();
  return s;
}

void LabApp::draw_view(const render::ViewSettings& s, int x, int y, int w, int h) {
  const render::Gl& gl = window_->gl();
  if (!sim_view_ || w < 1 || h < 1) return;
  if (view != LabView::Alioscopy && view != LabView::Grid) {
    // a flat view, or one camera of the rig (the single view)
    if (view != LabView::Single) {
      draw_flat(render::ViewProjection::of(camera_, double(w) / h), s, x, y, w, h);
      return;
    }
    const render::StereoRig rig = render::DisplayProfile{}.rig(render::StereoRig{});
    draw_flat(rig.view(camera_, std::clamp(single_view, 0, rig.views - 1), double(w) / h), s, x, y,
              w, h);
    return;
  }
  // Alioscopy: the interleaved image covers the whole window, pixel for
  // pixel, with the window's screen position; the grid the viewport.
  if (!alioscopy_) alioscopy_ = std::make_unique<render::AlioscopyOutput>(gl, render::DisplayProfile{});
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_->handle(), &fw, &fh);
  const int ow = view == LabView::Alioscopy ? fw : w, oh = view == LabView::Alioscopy ? fh : h;
  alioscopy_->resize_output(ow, oh);
  alioscopy_->render_views(*renderer_, render::StereoRig{}, camera_, geometry_, s);
  int wx = 0, wy = 0;
  window_->position(&wx, &wy);
  alioscopy_mode_ = view == LabView::Alioscopy ? render::AlioscopyOutput::Mode::Interleaved
                    : view == LabView::Grid    ? render::AlioscopyOutput::Mode::Grid
                                               : render::AlioscopyOutput::Mode::Single;
  alioscopy_window_ = {wx, wy};
  const int dx = view == LabView::Alioscopy ? 0 : x, dy = view == LabView::Alioscopy ? 0 : y;
  alioscopy_->compose_into(0, {dx, dy}, alioscopy_mode_, single_view, alioscopy_window_);
}

// Draws a flat view into the viewport at x, y (w x h, GL pixels).
// Adaptive resolution: llvmpipe is fill-bound, so the view renders at a
// scale that keeps the drawing near 20 ms (>= 30 frames per second with the
// solver's share), and is scaled up into the viewport.
void LabApp::draw_flat(const render::ViewProjection& vp, const render::ViewSettings& s, int x,
                       int y, int w, int h) {
  const render::Gl& gl = window_->gl();
  const double target_ms = 20;
  if (render_ms_ > 0)
    render_scale_ = std::clamp(render_scale_ * std::sqrt(target_ms / render_ms_), 0.35, 1.0);
  const int rw = std::max(1, int(w * render_scale_)), rh = std::max(1, int(h * render_scale_));
  const auto r0 = Clock::now();
  renderer_->resize(rw, rh);
  renderer_->draw(vp, geometry_, s);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, renderer_->framebuffer());
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  gl.BlitFramebuffer(0, 0, rw, rh, x, y, x + w, y + h, GL_COLOR_BUFFER_BIT,
                     rw == w ? GL_NEAREST : GL_LINEAR);
  gl.Finish();
  render_ms_ = 0.7 * render_ms_ + 0.3 * ms_since(r0);
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

// "view k" over each view of the grid (x, top: the grid's top-left corner
// in framebuffer pixels from the window's top left).
void LabApp::label_grid(int x, int top, int w, int h) {
  const render::GridLayout g = render::grid_layout(w, h, double(w) / std::max(1, h));
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  ImDrawList* list = ImGui::GetBackgroundDrawList();  // over the 3D view, under the panels
  for (int k = 0; k < render::kAlioscopyViews; ++k) {
    const plot::Rect c = g.cell(k, w, h, double(w) / std::max(1, h));
    const ImVec2 at((x + c.x0) / scale.x + 6, (top + c.y0) / scale.y + 4);
    list->AddText(at, IM_COL32(236, 238, 242, 255), ("view " + std::to_string(k)).c_str());
  }
}

void LabApp::save_screenshot(const std::string& path) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_->handle(), &fw, &fh);
  plot::Image img = render::read_framebuffer(window_->gl(), 0, fw, fh, GL_BACK);
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;  // the window's alpha is not ours
  plot::write_png(img, path);
}

void LabApp::save_frame(const std::string& path) {
  if (view == LabView::Alioscopy && alioscopy_) {
    // the window got the interleaved image straight; compose it once more
    // into the output's own framebuffer to read it
    alioscopy_->compose(alioscopy_mode_, single_view, alioscopy_window_);
    plot::write_png(alioscopy_->read_pixels(), path);
    return;
  }
  plot::write_png(renderer_->read_pixels(), path);
}

// Ends the drawing's part of a frame however it is left: the worker stops
// stepping on and is waited for (its exception, if any, is dropped: the
// one leaving is the drawing's).
struct LabApp::StopWhenLeaving {
  std::atomic<bool>& drawing;
  std::future<void>& stepping;
  ~StopWhenLeaving() {
    drawing = false;
    if (stepping.valid()) stepping.wait();
  }
};

void LabApp::handle_close() {
  GLFWwindow* w = window_->handle();
  if (!glfwWindowShouldClose(w)) return;
  glfwSetWindowShouldClose(w, GLFW_FALSE);
  const LabStage st = exp_->stage();
  if (script_ || st == LabStage::Empty || st == LabStage::Prepared || st == LabStage::Done)
    quit_ = true;
  else
    close_asked_ = true;  // ask whether to save a checkpoint first
}

// Where the panel, the 3D view and the plots column go; the panel's width.
int LabApp::lay_out_window(int fw, int fh) {
  const int panel = view == LabView::Alioscopy ? 0 : int(kPanelWidth);
  // the live plots in a column at the right, the 3D view between
  const bool plots = view != LabView::Alioscopy && exp_->apparatus() != nullptr;
  // at least 300 px, but never more than half of what the panel leaves
  plots_width_ = plots ? int(std::min(std::clamp(0.28f * float(fw - panel), 300.f, 520.f),
                                      0.5f * float(std::max(0, fw - panel))))
                       : 0;
  view_x_ = panel;
  view_y_ = 0;
  view_w_ = std::max(1, fw - panel - plots_width_);
  view_h_ = std::max(1, fh);
  return panel;
}

void LabApp::record_frame(long long steps) {
  if (!record_ || !sim_view_ || (frame_no_++ % std::max(1, record_every_)) != 0) return;
  char name[64];
  std::snprintf(name, sizeof name, "/frames/frame_%09lld.png", steps);
  std::filesystem::create_directories(std::string(out_path_) + "/frames");
  save_frame(out_path_ + std::string(name));
}

int LabApp::run() {
  GLFWwindow* w = window_->handle();
  auto last = Clock::now();
  while (!quit_) {
    // What reads or changes the experiment, with the solver idle: input,
    // background builds, the script, the panel's widgets, the beads packed
    // for the view (OpenCL).
    const auto f0 = Clock::now();
    glfwPollEvents();
    handle_close();
    act(exp_->poll());
    if (script_) run_script();
    attach_view();  // after anything that may have replaced the simulation
    refit_on_stage();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    poll_input();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(w, &fw, &fh);
    const int panel = lay_out_window(fw, fh);
    render::ViewSettings settings = sim_view_ ? pack_view() : render::ViewSettings{};
    draw_panel(panel);
    if (exp_->generation() != generation_) {  // the panel loaded or rebuilt a simulation
      attach_view();
      if (sim_view_) settings = pack_view();
    }
    const long long steps = exp_->simulation() ? exp_->simulation()->steps() : 0;
    if (view == LabView::Grid && sim_view_)
      label_grid(view_x_, fh - (view_y_ + view_h_), view_w_, view_h_);
    ImGui::Render();

    // Then the solver steps on a worker thread, for what the 1/30 s frame
    // leaves after the last drawing, while this one draws, and on while the
    // drawing lasts. Where both would run on the same CPU cores (llvmpipe
    // and a CPU OpenCL device) they take turns instead: overlapped there,
    // each only slowed the other.
    std::atomic<bool> drawing{true};
    const double budget = std::max(0.004, 1.0 / 30 - (ms_since(f0) + draw_ms_) * 1e-3);
    const bool overlap = !window_->software_rasterizer() || device_->is_gpu();
    auto stepping = std::async(std::launch::async, [&] {
      exp_->advance(budget, overlap ? &drawing : nullptr);
    });
    // should the drawing throw, the worker stops at its next chunk
    const StopWhenLeaving stop{drawing, stepping};
    if (!overlap) stepping.wait();
    const auto d0 = Clock::now();
    const render::Gl& gl = window_->gl();
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, fw, fh);
    gl.ClearColor(0.086f, 0.094f, 0.11f, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT);
    draw_view(settings, view_x_, view_y_, view_w_, view_h_);
    record_frame(steps);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (script_ && script_pending_screenshot()) take_script_screenshot();
    glfwSwapBuffers(w);
    draw_ms_ = ms_since(d0);
    drawing = false;
    stepping.get();
    if (std::string f = exp_->take_fault(); !f.empty())
      message_ = "stopped: " + f + " (paused at the step before; save a checkpoint to study it)";
    const double since = std::chrono::duration<double>(Clock::now() - last).count();
    last = Clock::now();
    fps_ = fps_ == 0 ? 1 / since : 0.9 * fps_ + 0.1 / since;
  }
  return exit_status_;
}

}  // namespace simsols
