// The lab's control panel (Dear ImGui): experiment, loading, view, output,
// live plots, the status line, the help overlay and the close dialog. Every
// button calls the same LabExperiment action as the keyboard and scripts.
#define GLFW_INCLUDE_NONE  // GL comes from render/gl/gl_api.h
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/experiment/shear_box/accuracy_table.h"
#include "app/lab/lab_app.h"
#include "app/lab/lab_plots.h"
#include "app/experiment/shear_box/paper_tests.h"
#include "solver/core/slots.h"
#include "solver/apparatus/run_profile.h"

namespace simsols {

namespace {

const char* kViews[] = {"flat opaque", "flat transparent", "force chains",
                        "Alioscopy (full screen)", "eight-view grid", "single view"};
const char* kPresets[] = {"front", "side", "top", "three-quarter"};


}  // namespace

void LabApp::draw_panel(int panel_width) {
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_->handle(), &fw, &fh);
  if (panel_width > 0) {
    ImGui::SetNextWindowPos({0, 0});
    ImGui::SetNextWindowSize({float(panel_width), float(fh)});
    ImGui::Begin("SimSols lab", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    draw_controls();
    ImGui::End();
    draw_plots();
  } else {
    // Alioscopy full screen: a small overlay to get back
    ImGui::SetNextWindowPos({10, 10});
    ImGui::Begin("##back", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoTitleBar);
    if (ImGui::Button("Back to the flat view")) view = LabView::Transparent;
    ImGui::End();
  }
  draw_status();
  if (help_) draw_help();
  if (close_asked_) draw_close_dialog();
}

// The panel's sections, in the order of a bench test (docs/lab.md). The
// stage is read once per frame: a button that changes it takes effect in the
// other sections at the next frame.
void LabApp::draw_controls() {
  const LabStage stage = exp_->stage();
  draw_stage_and_message(stage);
  if (ImGui::CollapsingHeader("Specimen", ImGuiTreeNodeFlags_DefaultOpen)) draw_specimen(stage);
  if (ImGui::CollapsingHeader("Loading and test", ImGuiTreeNodeFlags_DefaultOpen))
    draw_loading_and_running(stage);
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) draw_view_settings();
  if (ImGui::CollapsingHeader("Save")) draw_save();
}

// The scene, the stage, and the last error or note with a button to dismiss it.
void LabApp::draw_stage_and_message(LabStage stage) {
  ImGui::TextColored({0.55f, 0.8f, 1, 1}, "%s", exp_->scene_label().c_str());
  ImGui::Text("stage: %s%s", exp_->stage_text().c_str(),
              exp_->paused() && (stage == LabStage::Loading || stage == LabStage::Running) ? " (paused)" : "");
  if (!message_.empty()) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored({1, 0.45f, 0.35f, 1}, "%s", message_.c_str());
    ImGui::PopTextWrapPos();
    if (ImGui::SmallButton("dismiss")) message_.clear();
  }
}

// Step 1 of a test: the apparatus, a preset or a scene file, the precision,
// the time step and the effect slots, then Prepare / Reset.
void LabApp::draw_specimen(LabStage stage) {
  draw_apparatus_choice();
  draw_build_choices();
  draw_preset_and_scene_file();
  draw_precision_and_time_step();
  if (draw_effect_slots()) {
    message_ = "effects and precision apply when the specimen is prepared again (Reset): the "
               "kernels are rebuilt in the background";
  }
  ImGui::BeginDisabled(stage == LabStage::Building);
  if (ImGui::Button("Prepare / Reset (R)")) act(exp_->reset());
  ImGui::EndDisabled();
}

// Shear box, triaxial cell or oedometer: choosing one loads its default
// scene (the shear box's preset, the others' built-in scenes) and prepares it.
void LabApp::draw_apparatus_choice() {
  ImGui::SetNextItemWidth(150);
  const auto benches = lab_benches();
  const auto name = [](void* data, int i, const char** out) {
    *out = static_cast<const LabBench*>(data)[i].panel_name;
    return true;
  };
  if (ImGui::Combo("apparatus", &apparatus_, name, const_cast<LabBench*>(benches.data()),
                   int(benches.size()))) {
    message_.clear();
    const std::string err = exp_->load_default(benches[size_t(apparatus_)]);
    act(err);
    if (err.empty()) act(exp_->prepare());
  }
}

// The apparatus' own build choices (the triaxial's cell): choosing one
// prepares the specimen again with it.
void LabApp::draw_build_choices() {
  for (const LabChoice& c : exp_->choices()) {
    ImGui::SetNextItemWidth(150);
    if (!ImGui::BeginCombo(c.label.c_str(), c.options[size_t(c.current)].c_str())) continue;
    for (size_t i = 0; i < c.options.size(); ++i)
      if (ImGui::Selectable(c.options[i].c_str(), int(i) == c.current) && int(i) != c.current) {
        message_.clear();
        const std::string err = exp_->choose(c.key, c.options[i]);
        act(err);
        if (err.empty()) act(exp_->prepare());
      }
    ImGui::EndCombo();
  }
}

// The shear box: a Table 1 size and a paper stress (Preset); the others: their
// built-in scene (Default); or the scene file typed in the field (Open), of
// any apparatus. Each prepares the specimen at once.
void LabApp::draw_preset_and_scene_file() {
  const LabBench& bench = lab_benches()[size_t(apparatus_)];
  if (bench.default_scene_text) {
    if (ImGui::Button("Default scene")) {
      message_.clear();
      const std::string err = exp_->load_default(bench);
      act(err);
      if (err.empty()) act(exp_->prepare());
    }
  } else {
    draw_presets();
  }
  ImGui::SetNextItemWidth(300);
  ImGui::InputText("##scene", scene_path_, sizeof scene_path_);
  ImGui::SameLine();
  if (ImGui::Button("Open")) {
    message_.clear();
    const std::string err = exp_->load_scene_file(scene_path_);
    act(err);  // a failed load keeps the current experiment
    if (err.empty()) {
      apparatus_ = lab_bench_index(exp_->scene());
      act(exp_->prepare());
    }
  }
  ImGui::SetNextItemWidth(300);
  ImGui::InputTextWithHint("##calibrated", "calibrated.toml (simsols calibrate)", calibrated_path_,
                           sizeof calibrated_path_);
  ImGui::SameLine();
  if (ImGui::Button("Material")) {
    message_.clear();
    const std::string err = use_calibration(calibrated_path_, "");
    act(err);
    if (err.empty() || err.rfind("not a material", 0) == 0) act(exp_->prepare());
  }
  if (calibration_.loaded())
    ImGui::TextDisabled("calibrated material; measured: %s", calibration_.target().c_str());
}

std::string LabApp::use_calibration(const std::string& path, const std::string& target) {
  const std::string err = calibration_.load(path, target);
  if (!err.empty()) return err;
  return exp_->set_materials(calibration_.values());
}

void LabApp::draw_presets() {
  static const char* sizes[] = {"2.38 mm (8 layers)", "3.18 mm (6)", "3.97 mm (5)", "4.76 mm (4)",
                                "6.35 mm (4)"};
  static const char* stresses[] = {"50 kPa", "160 kPa", "280 kPa", "400 kPa"};
  ImGui::SetNextItemWidth(150);
  ImGui::Combo("##size", &preset_size_, sizes, 5);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(100);
  ImGui::Combo("##stress", &preset_stress_, stresses, 4);
  ImGui::SameLine();
  if (ImGui::Button("Preset")) {
    message_.clear();
    const std::string err = exp_->load_preset(kTable1SizesMm[preset_size_], kPaperStressesKpa[preset_stress_]);
    act(err);
    if (err.empty()) act(exp_->prepare());
  }
}

// The run profile (run_profile.h): paper, or a faster one applied at the
// next prepare on top of the settings below.
void LabApp::draw_profile() {
  const auto profiles = run_profiles();
  int current = 0;
  for (size_t i = 0; i < profiles.size(); ++i)
    if (exp_->profile() == profiles[i].name) current = int(i);
  ImGui::SetNextItemWidth(150);
  if (ImGui::BeginCombo("profile", profiles[current].name)) {
    for (size_t i = 0; i < profiles.size(); ++i)
      if (ImGui::Selectable(profiles[i].name, int(i) == current)) {
        exp_->set_profile(profiles[i].name);
        message_ = std::string("profile ") + profiles[i].name + ": " + profiles[i].summary +
                   "; applies when the specimen is prepared again (Reset)";
      }
    ImGui::EndCombo();
  }
}

// Float or double, the time step as a fraction of the Rayleigh time, and
// what the accuracy study measured for these settings on the specimen most
// like this one (docs/accuracy.md).
void LabApp::draw_precision_and_time_step() {
  draw_profile();
  int precision = exp_->scene().numerics.precision == Precision::Float ? 0 : 1;
  ImGui::Text("precision");
  ImGui::SameLine();
  bool changed = ImGui::RadioButton("float", &precision, 0);
  ImGui::SameLine();
  changed |= ImGui::RadioButton("double", &precision, 1);
  if (changed) exp_->set_precision(precision == 0 ? Precision::Float : Precision::Double);
  float dt_fraction = float(exp_->scene().numerics.dt_fraction);
  ImGui::SetNextItemWidth(200);
  if (ImGui::SliderFloat("time step (x Rayleigh)", &dt_fraction, 0.05f, 0.5f, "%.2f"))
    exp_->set_dt_fraction(dt_fraction);
  const std::optional<StudySpecimen> kind = accuracy_study_specimen(exp_->scene());
  if (!kind) return;  // the accuracy study measured shear tests only
  const ImVec4 grey = ImGui::GetStyle().Colors[ImGuiCol_TextDisabled];
  if (!run_profile(exp_->profile()).neutral()) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored(grey, "%s", profile_accuracy_text(exp_->profile(), *kind).c_str());
    ImGui::PopTextWrapPos();
    return;
  }
  if (const SettingSummary* a =
          expected_accuracy(dt_fraction, exp_->scene().numerics.precision, *kind)) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored(grey, "%s", expected_accuracy_text(*a).c_str());
    ImGui::PopTextWrapPos();
  }
}

// Steps 2 to 4, with the apparatus' words: apply the stress (the normal
// stress, sigma3), start the measured stage (shear, compression, the load
// programme), pause or step it, change the live settings while it runs,
// and where the test stands (the load step, equilibrium, the last row).
void LabApp::draw_loading_and_running(LabStage stage) {
  LabApparatus* a = exp_->apparatus();
  if (!a) {
    ImGui::TextDisabled("prepare a specimen first");
    return;
  }
  if (const char* load = a->load_label()) {
    ImGui::BeginDisabled(stage != LabStage::Prepared);
    if (ImGui::Button(load)) act(exp_->apply_load());
    ImGui::EndDisabled();
    ImGui::SameLine();
  }
  ImGui::BeginDisabled(stage == LabStage::Running || stage == LabStage::Done ||
                       stage == LabStage::Building);
  if (ImGui::Button(a->start_label())) act(exp_->start());
  ImGui::EndDisabled();
  if (ImGui::Button(exp_->paused() ? "Resume (space)" : "Pause (space)"))
    exp_->paused() ? exp_->resume() : exp_->pause();
  ImGui::SameLine();
  if (ImGui::Button("Step (S)")) act(exp_->step());
  draw_settings();
  if (const std::string p = a->progress_text(); !p.empty()) {
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(p.c_str());
    ImGui::PopTextWrapPos();
  }
}

// The live settings, each applied when Enter is pressed (the field shows
// the test's value while it is not being edited).
void LabApp::draw_settings() {
  LabApparatus* a = exp_->apparatus();
  for (const LabSetting& s : a->settings()) {
    float v = float(s.value);
    const std::string label = s.label + " (" + s.unit + ")";
    ImGui::SetNextItemWidth(160);
    if (ImGui::InputFloat(label.c_str(), &v, 0, 0, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue))
      act(exp_->set(s.key, double(v)));
  }
}

// The view, the beads' colour, the chain threshold and overlay, the camera.
void LabApp::draw_view_settings() {
  int v = int(view);
  ImGui::SetNextItemWidth(200);
  if (ImGui::Combo("view", &v, kViews, 6)) view = LabView(v);
  if (view == LabView::Single) {
    ImGui::SetNextItemWidth(200);
    ImGui::SliderInt("view index", &single_view, 0, 7);
  }
  int f = int(field);
  ImGui::SetNextItemWidth(200);
  const auto name = [](void*, int k, const char** out) {
    *out = to_string(kColorFields[k]);
    return true;
  };
  if (ImGui::Combo("colour by", &f, +name, nullptr, int(std::size(kColorFields)))) {
    field = kColorFields[f];
    field_chosen = true;
  }
  if (field == ColorField::Grain) ImGui::TextDisabled("one colour per grain (clump or sphere)");
  ImGui::SetNextItemWidth(200);
  ImGui::SliderFloat("chain threshold (F/F mean)", &threshold, 0, 4, "%.2f");
  ImGui::Checkbox("force chains over the beads", &chains_overlay);
  // a slab through the middle of the specimen, to see inside it
  const char* sections[] = {"whole specimen", "slab normal to x", "slab normal to y",
                            "slab normal to z"};
  int cut = section.axis + 1;
  ImGui::SetNextItemWidth(200);
  if (ImGui::Combo("section", &cut, sections, 4)) section.axis = cut - 1;
  if (section.on()) {
    ImGui::SetNextItemWidth(200);
    ImGui::SliderFloat("slab width (bead diameters)", &section.width, 0.5f, 10.f, "%.1f");
  }
  int p = int(preset_);
  ImGui::SetNextItemWidth(200);
  if (ImGui::Combo("camera", &p, kPresets, 4)) {
    preset_ = render::ViewPreset(p);
    fit_view();
  }
  ImGui::SameLine();
  if (ImGui::Button("Fit (F)")) fit_view();
}

// Saving into the folder field: a frame, a frame sequence, a checkpoint,
// the results; loading a checkpoint from the scene field.
void LabApp::draw_save() {
  ImGui::SetNextItemWidth(300);
  ImGui::InputText("folder", out_path_, sizeof out_path_);
  const std::string dir = out_path_;
  auto stamp = [&](const char* stem, const char* ext) {
    std::filesystem::create_directories(dir);
    const long long step = exp_->simulation() ? exp_->simulation()->steps() : 0;
    return dir + "/" + stem + "_" + std::to_string(step) + ext;
  };
  if (ImGui::Button("Frame (PNG)")) {
    const std::string f = stamp(view == LabView::Alioscopy ? "alioscopy" : "frame", ".png");
    save_frame(f);
    message_ = "saved " + f;
  }
  ImGui::SameLine();
  ImGui::Checkbox("record frames", &record_);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("every", &record_every_);
  if (ImGui::Button("Save checkpoint")) {
    const std::string f = stamp("checkpoint", ".bin");
    const std::string err = exp_->save_checkpoint(f);
    message_ = err.empty() ? "saved " + f : err;
  }
  ImGui::SameLine();
  if (ImGui::Button("Load checkpoint")) {
    const std::string err = exp_->load_checkpoint(scene_path_);
    message_ = err.empty() ? std::string("loaded ") + scene_path_ : err;
  }
  ImGui::SameLine();
  if (ImGui::Button("Export CSV + plots")) {
    const std::string err = exp_->export_results(dir);
    message_ = err.empty() ? "exported into " + dir : err;
  }
  ImGui::TextDisabled("Load checkpoint reads the path in the scene field.");
}

// The apparatus' live plots (LabApparatus::live_plots), stacked in the
// column right of the 3D view, all of them in its height (no scrolling).
void LabApp::draw_plots() {
  LabApparatus* a = exp_->apparatus();
  if (!a || plots_width_ <= 0) return;
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_->handle(), &fw, &fh);
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  ImGui::SetNextWindowPos({float(fw - plots_width_) / scale.x, 0});
  ImGui::SetNextWindowSize({float(plots_width_) / scale.x, float(fh) / scale.y});
  ImGui::Begin("Live plots", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoScrollbar);
  std::vector<LabPlot> plots = a->live_plots();
  calibration_.overlay(plots);
  measured_shown_ = 0;
  for (const LabPlot& p : plots) measured_shown_ += p.measured_x.size();
  if (plots.empty()) {
    plots_shown_ = 0;
    ImGui::End();
    return;
  }
  const float w = ImGui::GetContentRegionAvail().x, spacing = ImGui::GetStyle().ItemSpacing.y;
  const float h = (ImGui::GetContentRegionAvail().y - spacing * float(plots.size() - 1)) /
                  float(std::max<std::size_t>(1, plots.size()));
  for (std::size_t i = 0; i < plots.size(); ++i)
    draw_lab_plot(("##plot" + std::to_string(i)).c_str(), plots[i], w, std::max(80.0f, h));
  // what fits (scripts' state files): plots whose bottom lies inside the window
  plots_shown_ = ImGui::GetCursorScreenPos().y - spacing <= float(fh) / scale.y + 0.5f ? int(plots.size()) : -1;
  plot_height_ = h * scale.y;
  ImGui::End();
}

void LabApp::draw_status() {
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  const float width = float(view_w_) / scale.x - 16;
  ImGui::SetNextWindowPos({float(view_x_) / scale.x + 8, float(view_h_) / scale.y - 8}, 0, {0, 1});
  ImGui::SetNextWindowSizeConstraints({0, 0}, {width, 1e6f});
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoInputs);
  ImGui::PushTextWrapPos(width - 8);
  Simulation* sim = exp_->simulation();
  if (sim) {
    const LabApparatus* a = exp_->apparatus();
    const double inertial = a ? a->inertial_number() : 0;
    ImGui::TextWrapped("t = %.5f s   %.0f steps/s   %d beads   %zu contacts   I = %.2g   dt = %.3g s   %s",
                sim->time(), exp_->steps_per_second(), sim->model().particles(), contacts_,
                inertial, sim->dt(), sim->model().config().double_precision ? "double" : "float");
    if (const std::string w = a ? a->warning() : std::string(); !w.empty())
      ImGui::TextColored({1.0f, 0.6f, 0.2f, 1.0f}, "%s", w.c_str());
    std::string device = sim->model().device().name();
    if (device.size() > 48) device = device.substr(0, 45) + "...";
    ImGui::TextWrapped("%s   %s   %.0f fps (view at %.0f%%)   H: help", device.c_str(),
                sim_view_ ? (sim_view_->bridge().shared() ? "buffers shared (CL-GL)" : "buffers copied")
                          : "",
                fps_, render_scale_ * 100);
    ImGui::TextWrapped("compiled: %s",
                compiled_slots_line(sim->scene(), sim->model().config()).c_str());
  } else {
    ImGui::Text("%s   %.0f fps   (H: help)", exp_->stage_text().c_str(), fps_);
  }
  ImGui::PopTextWrapPos();
  ImGui::End();
}

void LabApp::draw_help() {
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), 0, {0.5f, 0.5f});
  ImGui::Begin("Keyboard and mouse", &help_, ImGuiWindowFlags_AlwaysAutoResize);
  const char* keys[][2] = {{"Space", "pause / resume"},
                           {"S", "single step (one measurement row)"},
                           {"R", "reset: a fresh specimen"},
                           {"F", "fit the view to the specimen"},
                           {"F11", "full screen"},
                           {"H, F1", "this help; Esc closes it"},
                           {"left drag", "orbit"},
                           {"right drag", "pan"},
                           {"wheel", "zoom"}};
  for (auto& k : keys) ImGui::Text("%-12s %s", k[0], k[1]);
  ImGui::End();
}

void LabApp::draw_close_dialog() {
  ImGui::OpenPopup("Close the lab?");
  if (ImGui::BeginPopupModal("Close the lab?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("A test is running. Save a checkpoint before closing?");
    if (ImGui::Button("Save and close")) {
      std::filesystem::create_directories(out_path_);
      const std::string f = std::string(out_path_) + "/checkpoint_on_close.bin";
      const std::string err = exp_->save_checkpoint(f);
      if (err.empty()) {
        std::printf("saved %s\n", f.c_str());
        quit_ = true;
      } else {
        message_ = err;
      }
      close_asked_ = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Close without saving")) quit_ = true;
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) {
      close_asked_ = false;
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

}  // namespace simsols
