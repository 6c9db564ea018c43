// LabApp: the desktop lab. One window (LabWindow), the Dear ImGui panel,
// the renderer drawing the running experiment (LabExperiment) into the
// viewport beside the panel, and an optional script that drives the same
// actions as the panel (tests, demonstrations).
//
// Each frame, in order:
//   poll          input, background builds, the script's next command
//   pack_view     the beads and contacts into the GL buffers (OpenCL), the
//                 walls where they are
//   draw_panel    controls, live plots, status line, help overlay: built
//                 (ImGui::Render), drawn below
// everything so far with the solver idle, as it reads or changes the
// experiment; then, overlapped:
//   advance       on a worker thread: the solver steps for what the 1/30 s
//                 frame leaves after the last drawing, and on while the
//                 drawing lasts, in chunks of a quarter of that, so the
//                 window stays responsive however slow a step is
//   draw_view     on this thread, GL only: the specimen flat (opaque,
//                 transparent, chains) into the viewport, or the Alioscopy
//                 output (interleaved full screen, 8-view grid, one view)
//                 written 1:1; then the panel's draw data, the swap
// and the frame ends when both have. Where the drawing and the solver share
// the CPU cores (llvmpipe with a CPU OpenCL device) the two take turns.
// Closing the window during a test asks whether to save a checkpoint.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/gl/alioscopy.h"
#include "render/gl/camera.h"
#include "app/lab/lab_calibration.h"
#include "app/lab/lab_experiment.h"
#include "app/lab/lab_window.h"
#include "render/gl/renderer.h"
#include "render/view/sim_view.h"

namespace simsols {

struct LabOptions {
  std::string scene;   // open this scene (any apparatus) at start, else the 6.35 mm / 160 kPa preset
  std::string script;  // run these commands (see lab_script.cpp)
  int width = 1400, height = 860;
};

enum class LabView { Opaque, Transparent, Chains, Alioscopy, Grid, Single };

class LabApp {
 public:
  explicit LabApp(const LabOptions& options);
  ~LabApp();
  int run();  // the main loop; returns the exit status

  // Actions shared by the panel, the keyboard and the script.
  void act(const std::string& error);  // shows an action's error in the panel
  LabExperiment& experiment() { return *exp_; }
  void fit_view();
  void draw_profile();
  void draw_build_choices();
  void refit_on_stage();
  void save_screenshot(const std::string& path);
  void save_frame(const std::string& path);  // the viewport only (or the Alioscopy image)
  std::string state_text();                  // key = value lines (scripts, tests)

  // view settings (public: the script sets them too)
  LabView view = LabView::Transparent;
  int single_view = 3;
  // The beads' colouring: until one is chosen (panel or script), each
  // experiment's default (grain with clumps, else layer).
  ColorField field = ColorField::Layer;
  bool field_chosen = false;
  float threshold = 1.0f;
  bool chains_overlay = false;
  render::Section section;  // a slab through the middle, or the whole specimen

 private:
  struct Script;
  struct StopWhenLeaving;
  void poll_input();
  void run_script();
  bool script_pending_screenshot() const;
  void take_script_screenshot();
  void attach_view();
  void handle_close();
  int lay_out_window(int framebuffer_width, int framebuffer_height);
  render::ViewSettings pack_view();
  void draw_view(const render::ViewSettings& s, int x, int y, int w, int h);
  void record_frame(long long steps);
  void draw_flat(const render::ViewProjection& vp, const render::ViewSettings& s, int x, int y,
                 int w, int h);
  void label_grid(int x, int top, int w, int h);
  void draw_panel(int panel_width);
  void draw_controls();  // the panel's sections, one function each (lab_panel.cpp):
  void draw_stage_and_message(LabStage stage);
  void draw_specimen(LabStage stage);
  void draw_apparatus_choice();
  void draw_preset_and_scene_file();
  void draw_presets();
  void draw_precision_and_time_step();
  void draw_loading_and_running(LabStage stage);
  void draw_settings();
  void draw_view_settings();
  void draw_save();
  bool draw_effect_slots();  // lab_effects.cpp; true when a slot changed
  void draw_plots();   // in the column right of the 3D view
  void draw_status();  // under the 3D view, wrapped to its width
  // Loads a calibrated.toml (its measured curve `target`, "" = the first)
  // and applies its material to the scene of the next preparation.
  std::string use_calibration(const std::string& path, const std::string& target);
  void draw_help();
  void draw_close_dialog();

  LabOptions opt_;
  std::unique_ptr<LabWindow> window_;
  std::shared_ptr<Device> device_;
  std::unique_ptr<LabExperiment> exp_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::AlioscopyOutput> alioscopy_;
  render::AlioscopyOutput::Mode alioscopy_mode_ = render::AlioscopyOutput::Mode::Interleaved;
  glm::ivec2 alioscopy_window_{0, 0};  // the window's screen position when last composed
  LabView look_ = LabView::Transparent;  // the last flat view: the stereo views' look
  std::unique_ptr<render::SimulationView> sim_view_;
  render::FrameGeometry geometry_;  // packed for this frame (pack_view)
  render::Camera camera_;
  render::ViewPreset preset_ = render::ViewPreset::ThreeQuarter;
  int generation_ = -1;
  LabStage fitted_stage_ = LabStage::Empty;  // the stage the view was last framed for
  std::string message_;  // last error or note, shown in the panel
  bool help_ = false, close_asked_ = false, quit_ = false;
  double draw_ms_ = 0, fps_ = 0;
  std::size_t contacts_ = 0;  // touching contacts drawn last frame
  double render_ms_ = 0, render_scale_ = 1;  // flat view: adaptive resolution
  std::unique_ptr<Script> script_;
  int exit_status_ = 0;
  // panel state
  int apparatus_ = 0;  // the panel's choice: an index into lab_benches()
  int preset_size_ = 4, preset_stress_ = 1;
  char scene_path_[512] = "";
  char calibrated_path_[512] = "";  // a calibration's calibrated.toml
  LabCalibration calibration_;      // its material and measured curve
  std::size_t measured_shown_ = 0;  // measured points over the live plots last frame
  char out_path_[512] = "results/lab";
  bool record_ = false;
  int record_every_ = 5, frame_no_ = 0;
  int dragging_ = -1;
  double last_x_ = 0, last_y_ = 0;
  int view_x_ = 0, view_y_ = 0, view_w_ = 1, view_h_ = 1;
  int plots_width_ = 0;  // the live plots' column at the right (0: none)
  int plots_shown_ = 0;  // live plots drawn last frame, all inside the window (-1: some cut)
  float plot_height_ = 0;  // pixels each
};

int run_lab(const LabOptions& options);

}  // namespace simsols
