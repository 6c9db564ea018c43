#include "app/lab/lab_experiment.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "solver/io/checkpoint.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "app/experiment/paper_tests.h"
#include "solver/io/scene_toml.h"
#include "app/experiment/shear_plots.h"

namespace simsols {

namespace {
constexpr const char* kStateTag = "lab_experiment 1\n";
}

const char* to_string(LabStage s) {
  switch (s) {
    case LabStage::Empty: return "no specimen";
    case LabStage::Building: return "building the specimen";
    case LabStage::Prepared: return "specimen prepared";
    case LabStage::Loading: return "applying the normal stress";
    case LabStage::Loaded: return "normal stress applied";
    case LabStage::Shearing: return "shearing";
    case LabStage::Done: return "shear finished";
  }
  return "?";
}

LabExperiment::LabExperiment(std::shared_ptr<Device> device) : device_(std::move(device)) {}

LabExperiment::~LabExperiment() {
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
    const Scene base = parse_scene(default_shear_scene_text(), kDefaultSceneName);
    Scene sc = paper_test_scene(base, kDefaultSceneName, d_mm, s_kpa, 0,
                                [&](Scene& x) { x.numerics.precision = scene_.numerics.precision; });
    if (!label_.empty()) sc.effects = scene_.effects;  // keep the panel's choices
    validate_scene(sc, sc.name);
    scene_ = std::move(sc);
    label_ = "preset " + scene_.name;
    return {};
  } catch (const SceneError& e) {
    return given + (e.field.empty() ? "" : "field '" + e.field + "': ") + e.message;
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string LabExperiment::load_scene_file(const std::string& path) {
  try {
    Scene sc = load_scene(path);
    validate_scene(sc, path);
    if (!sc.shear_box)
      return path + ": the lab runs direct shear tests; this scene has no [shear_box] table";
    scene_ = std::move(sc);
    label_ = path;
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string LabExperiment::prepare() {
  if (label_.empty()) return "choose a preset or open a scene first";
  if (building_.valid()) return "a specimen is already being built";
  running_ = false;
  loading_started_ = false;
  auto device = device_;
  const Scene scene = scene_;
  building_ = std::async(std::launch::async,
                         [device, scene] { return std::make_unique<Simulation>(device, scene); });
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
  return {};
}

void LabExperiment::adopt(std::unique_ptr<Simulation> sim, const std::string& state) {
  auto test = std::make_unique<ShearTest>(*sim);
  test->hold_before_shear(true);
  if (!state.empty()) test->restore_state(state);
  test_ = std::move(test);
  sim_ = std::move(sim);
  ++generation_;
}

LabStage LabExperiment::stage() const {
  if (building_.valid()) return LabStage::Building;
  if (!sim_) return LabStage::Empty;
  if (test_->done()) return LabStage::Done;
  if (test_->phase() == ShearPhase::Shear) return LabStage::Shearing;
  if (test_->ready_to_shear()) return LabStage::Loaded;
  if (loading_started_ || sim_->steps() > 0) return LabStage::Loading;
  return LabStage::Prepared;
}

std::string LabExperiment::apply_normal_stress() {
  if (stage() != LabStage::Prepared) return "prepare a specimen first";
  loading_started_ = true;
  running_ = true;
  return {};
}

std::string LabExperiment::start_shear() {
  const LabStage s = stage();
  if (s != LabStage::Loaded && s != LabStage::Loading)
    return "apply the normal stress first";
  test_->start_shear();  // at once when consolidated, else as soon as it is
  running_ = true;
  return {};
}

std::string LabExperiment::step() {
  const LabStage s = stage();
  if (s != LabStage::Loading && s != LabStage::Shearing) return "nothing to step";
  running_ = false;
  if (s == LabStage::Shearing) {
    const size_t rows = test_->rows().size();
    while (test_->rows().size() == rows && !test_->done()) test_->advance(1 << 20);
  } else {
    test_->advance(200);
  }
  return {};
}

std::string LabExperiment::set_normal_stress(double pa) {
  if (!(pa > 0) || pa > 1e9) return "normal stress must be in (0, 1e6] kPa";
  scene_.shear_box->normal_stress = pa;
  if (test_) test_->set_normal_stress(pa);
  return {};
}

std::string LabExperiment::set_shear_speed(double v) {
  if (!(v > 0) || v > 1) return "shear speed must be in (0, 1000] mm/s";
  if (test_) test_->set_shear_speed(v);
  else scene_.shear_box->shear_speed = v;
  return {};
}

std::int64_t LabExperiment::advance(double budget) {
  if (!running_ || !sim_) return 0;
  const LabStage s = stage();
  if (s != LabStage::Loading && s != LabStage::Shearing) {
    if (s == LabStage::Done || s == LabStage::Loaded) running_ = false;
    return 0;
  }
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const std::int64_t first = sim_->steps();
  double elapsed = 0;
  while (elapsed < budget && !test_->done() && !(test_->ready_to_shear() && s == LabStage::Loading)) {
    if ((pause_rows_ > 0 && test_->rows().size() >= pause_rows_) ||
        (pause_step_ > 0 && sim_->steps() >= pause_step_)) {
      running_ = false;
      pause_rows_ = 0;
      pause_step_ = 0;
      break;
    }
    const auto c0 = Clock::now();
    std::int64_t n = chunk_;
    if (pause_step_ > 0) n = std::min<std::int64_t>(n, pause_step_ - sim_->steps());
    try {
      test_->advance(n);  // returns at each new row
    } catch (const RunawayError& e) {
      // the simulation is at the step before the fault: paused there
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
  if (test_->ready_to_shear() && s == LabStage::Loading) running_ = false;  // holding: wait
  return done;
}

std::string LabExperiment::save_checkpoint(const std::string& path) {
  if (!sim_) return "no experiment to save";
  try {
    simsols::save_checkpoint(*sim_, path,
                             std::string(kStateTag) + (loading_started_ ? "1\n" : "0\n") +
                                 test_->save_state());
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string LabExperiment::load_checkpoint(const std::string& path) {
  try {
    std::string extra;
    auto sim = simsols::load_checkpoint(device_, path, &extra);
    if (!sim->scene().shear_box) return path + ": not a shear test checkpoint";
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
  if (!test_ || test_->rows().empty()) return "no rows to export yet";
  try {
    std::filesystem::create_directories(dir);
    const std::string d = std::filesystem::path(dir).string();
    write_file_atomic(d + "/shear.csv", shear_rows_csv(test_->rows()));
    write_file_atomic(d + "/summary.txt", shear_summary_text(test_->summary()));
    write_shear_plots(d, scene_.name, test_->rows(), test_->summary());
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

}  // namespace simsols
