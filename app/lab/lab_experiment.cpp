#include "app/lab/lab_experiment.h"

#include "app/experiment/calibration/scene_keys.h"
#include "app/experiment/test_title.h"

#include "app/experiment/specimen_report.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/experiment/default_scenes.h"
#include "app/experiment/shear_box/paper_tests.h"
#include "solver/apparatus/run_profile.h"
#include "solver/common/errors.h"
#include "solver/io/checkpoint.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"

namespace simsols {

namespace {
constexpr const char* kStateTag = "lab_experiment 1\n";

std::string scene_error_text(const std::string& given, const SceneError& e) {
  return given + (e.field.empty() ? "" : "field '" + e.field + "': ") + e.message;
}
}  // namespace

// A preparation's files (density.csv, density.png, tamping's) go to a
// folder of this lab's own process.
LabExperiment::LabExperiment(std::shared_ptr<Device> device)
    : device_(std::move(device)),
      preparation_dir_((std::filesystem::temp_directory_path() /
                        ("simsols-lab-preparation-" + std::to_string(::getpid())))
                           .string()) {}

// A specimen still being prepared is stopped (PreparationStopped, between
// chunks of steps) rather than waited for.
LabExperiment::~LabExperiment() {
  if (news_) news_->cancel = true;
  if (building_.valid()) building_.wait();
}

std::string LabExperiment::load_preset(double d_mm, double s_kpa) {
  char given[96];
  std::snprintf(given, sizeof given, "preset %g mm, %g kPa: ", d_mm, s_kpa);
  if (!nearest_table1_size(d_mm))
    return given + std::string("the presets' sizes are ") + table1_sizes_text() + " (Table 1)";
  if (!(s_kpa > 0 && s_kpa <= 1e6))
    return given + std::string("the normal stress must be in (0, 1e6] kPa");
  try {
    const Scene base = default_shear_base();
    Scene sc = paper_test_scene(base, kDefaultSceneName, d_mm, s_kpa, 0,
                                [&](Scene& x) { x.numerics.precision = scene_.numerics.precision; });
    const std::string name = sc.name;
    return adopt_scene(std::move(sc), "preset " + name, name, true);
  } catch (const SceneError& e) {
    return scene_error_text(given, e);
  } catch (const std::exception& e) {
    return e.what();
  }
}

// The shear box's default is the lab's preset (6.35 mm, 160 kPa); the
// triaxial cell's and the oedometer's are their built-in scenes, in the
// precision chosen in the panel.
std::string LabExperiment::load_default(const LabBench& bench) {
  if (!bench.default_scene_text) return load_preset(6.35, 160);
  const char* name = bench.default_scene_name;
  try {
    Scene sc = read_scene_text(bench.default_scene_text(), name);
    sc.numerics.precision = scene_.numerics.precision;
    return adopt_scene(std::move(sc), name, name, true);
  } catch (const SceneError& e) {
    return scene_error_text(std::string(name) + ": ", e);
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string LabExperiment::load_scene_file(const std::string& path) {
  try {
    Scene sc = read_scene(path);  // placed by prepare()
    if (lab_bench_index(sc) < 0)
      return path + ": the lab runs the tests of the apparatus " + lab_kind_names() +
             "; this scene has none of those tables";
    return adopt_scene(std::move(sc), path, path, false);
  } catch (const std::exception& e) {
    return e.what();
  }
}

// Validates `sc` (named `source` in errors) and makes it the scene of the
// next prepare(); a built-in scene keeps the panel's effect choices once a
// scene has been chosen. Throws SceneError.
std::string LabExperiment::adopt_scene(Scene sc, const std::string& label,
                                       const std::string& source, bool keep_effects) {
  if (keep_effects && !label_.empty()) sc.effects = scene_.effects;
  validate_scene(sc, source);
  scene_ = std::move(sc);
  label_ = label;
  return {};
}

std::string LabExperiment::prepare() {
  if (label_.empty()) return "choose a preset or open a scene first";
  if (building_.valid()) return "a specimen is already being built";
  Scene profiled = scene_;
  try {
    apply_profile(profiled, run_profile(profile_), label_);
  } catch (const InputError& e) {
    return e.message;
  }
  running_ = false;
  loading_started_ = false;
  auto device = device_;
  news_ = std::make_shared<BuildNews>();
  building_ = std::async(std::launch::async, [device, scene = std::move(profiled), news = news_,
                                              dir = preparation_dir_]() mutable {
    const auto line = [&](const std::string& l) {
      const std::lock_guard lock(news->mutex);
      news->line = l;
    };
    place_scene(scene);
    const bool prepared = prepare_to_relative_density(
        scene, device, dir, PrepLog(line, [&news] { return news->cancel.load(); }));
    {
      const std::lock_guard lock(news->mutex);
      news->prepared = prepared;
    }
    return std::make_unique<Simulation>(device, scene);
  });
  return {};
}

std::string LabExperiment::reset() { return prepare(); }

std::string LabExperiment::poll() {
  if (!building_.valid() ||
      building_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return {};
  try {
    adopt(building_.get(), {});
  } catch (const std::exception& e) {
    building_ = {};
    return e.what();
  }
  const std::lock_guard lock(news_->mutex);
  // Reset builds the prepared specimen again (a profile's scene would be
  // profiled twice: it is searched again instead)
  if (news_->prepared && run_profile(profile_).neutral()) scene_ = sim_->scene();
  return {};
}

void LabExperiment::adopt(std::unique_ptr<Simulation> sim, const std::string& state) {
  std::unique_ptr<LabApparatus> app = make_lab_apparatus(*sim);
  if (!app) throw SceneError("bad_scene", sim->scene().name, 0, "", "the scene has no apparatus the lab runs");
  if (!state.empty()) app->programme().restore_state(state);
  app_ = std::move(app);
  sim_ = std::move(sim);
  ++generation_;
}

LabStage LabExperiment::stage() const {
  if (building_.valid()) return LabStage::Building;
  if (!sim_) return LabStage::Empty;
  return app_->stage(loading_started_ || sim_->steps() > 0);
}

std::string LabExperiment::stage_text() const {
  const LabStage s = stage();
  if (s == LabStage::Building && news_) {
    const std::lock_guard lock(news_->mutex);
    if (!news_->line.empty()) return std::string(to_string(s)) + ": " + news_->line;
  }
  return s == LabStage::Empty || s == LabStage::Building ? to_string(s) : app_->stage_text(s);
}

std::string LabExperiment::apply_load() {
  if (stage() != LabStage::Prepared) return "prepare a specimen first";
  if (std::string e = app_->begin_loading(); !e.empty()) return e;
  loading_started_ = true;
  running_ = true;
  return {};
}

std::string LabExperiment::start() {
  if (!app_) return "prepare a specimen first";
  const LabStage s = stage();
  if (s == LabStage::Building) return "the specimen is still being built";
  if (std::string e = app_->start(s); !e.empty()) return e;
  loading_started_ = true;
  running_ = true;
  return {};
}

std::string LabExperiment::step() {
  const LabStage s = stage();
  if (s != LabStage::Loading && s != LabStage::Running) return "nothing to step";
  running_ = false;
  LoadingProgramme& p = app_->programme();
  if (s == LabStage::Running) {
    const size_t rows = app_->rows();
    while (app_->rows() == rows && !p.done()) p.advance(1 << 20);
  } else {
    p.advance(200);
  }
  return {};
}

std::string LabExperiment::set_materials(const std::vector<std::pair<std::string, double>>& values) {
  Scene sc = scene_;
  const std::vector<std::string> not_set = set_material_values(sc, values);
  try {
    validate_scene(sc, label_);
  } catch (const std::exception& e) {
    return e.what();
  }
  scene_ = std::move(sc);
  std::string note;
  for (const std::string& k : not_set) note += (note.empty() ? "" : ", ") + k;
  return note.empty() ? "" : "not a material of this scene, not set: " + note;
}

std::vector<LabChoice> LabExperiment::choices() const {
  return app_ ? app_->choices(scene_) : std::vector<LabChoice>{};
}

std::string LabExperiment::choose(const std::string& key, const std::string& option) {
  if (!app_) return "prepare a specimen first";
  Scene sc = scene_;
  if (std::string e = app_->choose(key, option, sc); !e.empty()) return e;
  try {
    validate_scene(sc, label_);
  } catch (const std::exception& e) {
    return e.what();
  }
  scene_ = std::move(sc);
  return {};
}

std::string LabExperiment::set(const std::string& key, double value) {
  if (!app_) return "prepare a specimen first";
  const LabStage before = stage();
  if (std::string e = app_->set(key, value, scene_); !e.empty()) return e;
  // a new stress while loaded restarts the equilibrium checks: go on loading
  if (before == LabStage::Loaded && stage() == LabStage::Loading) running_ = true;
  return {};
}

bool LabExperiment::should_pause() const {
  return (pause_rows_ > 0 && app_->rows() >= pause_rows_) ||
         (pause_step_ > 0 && sim_->steps() >= pause_step_) ||
         (pause_stage_ && stage() == *pause_stage_);
}

std::int64_t LabExperiment::advance(double budget, const std::atomic<bool>* keep_going) {
  if (!running_ || !sim_) return 0;
  const LabStage s = stage();
  if (s != LabStage::Loading && s != LabStage::Running) {
    if (s == LabStage::Done || s == LabStage::Loaded) running_ = false;
    return 0;
  }
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const std::int64_t first = sim_->steps();
  LoadingProgramme& test = app_->programme();
  double elapsed = 0;
  const auto more = [&] { return elapsed < budget || (keep_going && keep_going->load()); };
  while (more() && !test.done() && !(app_->holding() && stage() == LabStage::Loaded)) {
    if (should_pause()) {
      running_ = false;
      pause_at(0, 0);
      break;
    }
    const auto c0 = Clock::now();
    std::int64_t n = chunk_;
    if (pause_step_ > 0) n = std::min<std::int64_t>(n, pause_step_ - sim_->steps());
    try {
      test.advance(n);  // returns at each new row and stage change
    } catch (const RunawayError& e) {
      // the simulation is at the step before the fault: paused there
      running_ = false;
      fault_ = e.what();
      break;
    } catch (const InputError& e) {  // a specimen the apparatus cannot take (a membrane too short)
      running_ = false;
      fault_ = e.what();
      break;
    }
    device_->finish();
    const double dt = std::chrono::duration<double>(Clock::now() - c0).count();
    elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    // aim for chunks of about a quarter of the budget
    if (dt > 0) chunk_ = std::clamp<std::int64_t>(std::llround(chunk_ * 0.25 * budget / dt), 1, 1 << 20);
  }
  const std::int64_t done = sim_->steps() - first;
  if (elapsed > 0 && done > 0) rate_ = 0.8 * rate_ + 0.2 * done / elapsed;
  if (app_->holding() && stage() == LabStage::Loaded) running_ = false;  // holding: wait
  if (running_ && should_pause()) {  // reached in the last chunk
    running_ = false;
    pause_at(0, 0);
  }
  return done;
}

std::string LabExperiment::save_checkpoint(const std::string& path) {
  if (!sim_) return "no experiment to save";
  try {
    simsols::save_checkpoint(*sim_, path,
                             std::string(kStateTag) + (loading_started_ ? "1\n" : "0\n") +
                                 app_->programme().save_state());
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string LabExperiment::load_checkpoint(const std::string& path) {
  try {
    std::string extra;
    auto sim = simsols::load_checkpoint(device_, path, &extra);
    if (lab_bench_index(sim->scene()) < 0)
      return path + ": not a checkpoint of a test the lab runs (" + lab_kind_names() + ")";
    bool started = true;
    if (extra.rfind(kStateTag, 0) == 0) {
      extra.erase(0, std::string(kStateTag).size());
      started = extra[0] == '1';
      extra.erase(0, 2);
    }
    scene_ = sim->scene();
    label_ = path;
    adopt(std::move(sim), extra);
    loading_started_ = started;
    running_ = false;
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string LabExperiment::export_results(const std::string& dir) {
  if (!app_ || app_->rows() == 0) return "no rows to export yet";
  try {
    std::filesystem::create_directories(dir);
    app_->export_results(std::filesystem::path(dir).string(), test_title(scene_));
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace simsols
