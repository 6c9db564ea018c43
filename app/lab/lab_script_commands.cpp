// The lab script's commands, one handler each (docs/lab.md, "Scripts"):
// each parses its own argument and calls the same action as the panel.
// A handler that starts something sets the script's end condition (`until`),
// so the next command waits until it is there. kCommands (lab_script.cpp)
// maps the names to these handlers.
#include <cmath>
#include <cstdio>
#include <functional>

#include "app/lab/lab_script.h"
#include "solver/apparatus/run_profile.h"
#include "solver/io/output.h"
#include "app/experiment/shear_box/paper_tests.h"
#include "solver/core/slots.h"
#include "solver/scene/choices.h"

namespace simsols {

namespace {

// A slot's choice by name (choices.h); false when the name is unknown.
template <typename E>
bool pick(E& field, const std::string& choice) {
  const std::optional<E> v = parse_choice<E>(choice);
  if (v) field = *v;
  return v.has_value();
}

// "damping viscous|none; tangential mindlin|none; ...": what `effect` takes.
std::string effect_choices() {
  return "damping " + choice_names_joined<DampingModel>() + "; tangential " + choice_names_joined<TangentialModel>() +
         "; rolling " + choice_names_joined<RollingModel>() + "; cohesion " + choice_names_joined<CohesionModel>() +
         "; fluid " + choice_names_joined<FluidModel>();
}

bool set_slot(Effects& e, const std::string& slot, const std::string& choice) {
  if (slot == "damping") return pick(e.damping, choice);
  if (slot == "tangential") return pick(e.tangential, choice);
  if (slot == "rolling") return pick(e.rolling, choice);
  if (slot == "cohesion") return pick(e.cohesion, choice);
  if (slot == "fluid") return pick(e.fluid, choice);
  return false;
}

}  // namespace

// ------------------------------------------------------------ the specimen

// The apparatus' default scene (the shear box's 6.35 mm / 160 kPa preset),
// as the panel's combo box.
void LabApp::Script::choose_apparatus(const Line& line) {
  const int bench = lab_bench_index(line.argument);
  if (bench < 0)
    return fail(line, "apparatus " + lab_kind_names() + ", got '" + line.argument + "'", 2);
  if (succeeded(line, experiment().load_default(lab_benches()[size_t(bench)])))
    lab.apparatus_ = bench;
}

void LabApp::Script::choose_preset(const Line& line) {
  double d = 0, kpa = 0;
  if (std::sscanf(line.argument.c_str(), "%lf %lf", &d, &kpa) != 2)
    return fail(line, "preset D_MM S_KPA", 2);
  if (!succeeded(line, experiment().load_preset(d, kpa))) return;
  lab.apparatus_ = lab_bench_index(experiment().scene());
  const double size = nearest_table1_size(d).value_or(d);
  for (int k = 0; k < 5; ++k)  // the panel's combo boxes follow
    if (kTable1SizesMm[k] == size) lab.preset_size_ = k;
  for (int k = 0; k < 4; ++k)
    if (std::fabs(kPaperStressesKpa[k] - kpa) < 1e-9) lab.preset_stress_ = k;
}

void LabApp::Script::open_scene(const Line& line) {
  if (succeeded(line, experiment().load_scene_file(line.argument)))
    lab.apparatus_ = lab_bench_index(experiment().scene());
}

void LabApp::Script::use_material(const Line& line) {
  const size_t space = line.argument.find(' ');
  const std::string path = line.argument.substr(0, space);
  const std::string target = space == std::string::npos ? "" : line.argument.substr(space + 1);
  const std::string err = lab.use_calibration(path, target);
  // a note on keys that are not a material's is not a failure
  if (err.rfind("not a material", 0) == 0) return;
  succeeded(line, err);
}

void LabApp::Script::choose_precision(const Line& line) {
  const std::optional<Precision> p = parse_choice<Precision>(line.argument);
  if (!p) return fail(line, "precision " + choice_names_joined<Precision>(), 2);
  experiment().set_precision(*p);
}

void LabApp::Script::choose_profile(const Line& line) {
  std::string names;
  for (const RunProfile& p : run_profiles()) {
    if (line.argument == p.name) return experiment().set_profile(p.name);
    names += (names.empty() ? "" : "|") + std::string(p.name);
  }
  fail(line, "profile " + names, 2);
}

// the apparatus' build choices: choose KEY OPTION (applies at the next prepare)
void LabApp::Script::choose_build(const Line& line) {
  char key[32] = {0}, option[32] = {0};
  if (std::sscanf(line.argument.c_str(), "%31s %31s", key, option) != 2)
    return fail(line, "choose KEY OPTION (the apparatus' choices: docs/lab.md)", 2);
  succeeded(line, experiment().choose(key, option));
}

// the panel's slot choices: effect SLOT CHOICE (applies at the next prepare)
void LabApp::Script::choose_effect(const Line& line) {
  char slot[32] = {0}, choice[32] = {0};
  if (std::sscanf(line.argument.c_str(), "%31s %31s", slot, choice) != 2)
    return fail(line, "effect SLOT CHOICE, one of: " + effect_choices(), 2);
  Effects e = experiment().scene().effects;
  if (!set_slot(e, slot, choice))
    return fail(line,
                "effect " + line.argument + ": unknown slot or choice; allowed: " + effect_choices(),
                2);
  experiment().set_effects(e);
}

void LabApp::Script::prepare(const Line& line) {
  LabExperiment& exp = experiment();
  if (succeeded(line, exp.prepare())) until = [&exp] { return exp.stage() == LabStage::Prepared; };
}

// ------------------------------------------------------- loading and test

// The stress (KPA, when given, first becomes the target: the shear box's
// normal stress, the triaxial cell's sigma3); waits until consolidated.
void LabApp::Script::apply_load(const Line& line) {
  LabExperiment& exp = experiment();
  if (!line.argument.empty()) {
    const std::optional<double> kpa = number(line);
    if (!kpa || !succeeded(line, exp.set("stress", *kpa))) return;
  }
  if (succeeded(line, exp.apply_load()))
    until = [&exp] { return exp.stage() == LabStage::Loaded || exp.stage() == LabStage::Done; };
}

// The measured stage starts (at once from Loaded; the oedometer settles
// first) and the run pauses exactly there; scripts then move on with
// `rows`, `steps`, `finish` or `resume`, so a session is the same every time.
void LabApp::Script::start(const Line& line) {
  LabExperiment& exp = experiment();
  if (!succeeded(line, exp.start())) return;
  exp.pause_at(0, 0, LabStage::Running);
  until = [&exp] {
    return (exp.stage() == LabStage::Running && exp.paused()) || exp.stage() == LabStage::Done;
  };
}

void LabApp::Script::run_rows(const Line& line) {
  const std::optional<double> v = number(line);
  if (!v) return;
  LabExperiment& exp = experiment();
  const std::size_t n = std::size_t(*v);
  exp.pause_at(n, 0);
  exp.resume();
  until = [&exp, n] {
    return !exp.apparatus() || exp.stage() == LabStage::Done || (exp.rows() >= n && exp.paused());
  };
}

void LabApp::Script::run_steps(const Line& line) {
  LabExperiment& exp = experiment();
  const std::optional<double> v = number(line);
  if (!v || !exp.simulation()) return;
  const std::int64_t target = exp.simulation()->steps() + std::int64_t(*v);
  exp.pause_at(0, target);
  exp.resume();
  until = [&exp, target] {
    return !exp.simulation() || (exp.simulation()->steps() >= target && exp.paused());
  };
}

// Runs until the test is done (the oedometer's programme, a compression),
// or until it holds, loaded.
void LabApp::Script::finish(const Line& line) {
  LabExperiment& exp = experiment();
  const LabStage st = exp.stage();
  if (st != LabStage::Loading && st != LabStage::Running && st != LabStage::Done)
    return fail(line, "finish: nothing is running; 'load' or 'start' first", 1);
  exp.resume();
  // a test that holds when loaded waits there for `start`
  until = [&exp] {
    return exp.stage() == LabStage::Done || (exp.stage() == LabStage::Loaded && exp.paused());
  };
}

void LabApp::Script::set_setting(const Line& line, const char* key) {
  if (const std::optional<double> v = number(line)) succeeded(line, experiment().set(key, *v));
}

void LabApp::Script::set_stress(const Line& line) { set_setting(line, "stress"); }

void LabApp::Script::set_speed(const Line& line) { set_setting(line, "speed"); }

void LabApp::Script::set_rate(const Line& line) { set_setting(line, "rate"); }

void LabApp::Script::pause(const Line&) { experiment().pause(); }

void LabApp::Script::resume(const Line&) { experiment().resume(); }

void LabApp::Script::step(const Line& line) { succeeded(line, experiment().step()); }

// ---------------------------------------------------------------- the view

void LabApp::Script::choose_view(const Line& line) {
  const std::pair<const char*, LabView> views[] = {
      {"opaque", LabView::Opaque},       {"transparent", LabView::Transparent},
      {"chains", LabView::Chains},       {"alioscopy", LabView::Alioscopy},
      {"grid", LabView::Grid},           {"single", LabView::Single}};
  for (auto [name, view] : views)
    if (line.argument == name) {
      lab.view = view;
      return;
    }
  fail(line, "view opaque|transparent|chains|alioscopy|grid|single", 2);
}

void LabApp::Script::choose_color(const Line& line) {
  if (auto f = parse_color_field(line.argument)) {
    lab.field = *f;
    lab.field_chosen = true;
  } else {
    fail(line, "color " + color_field_names('|'), 2);
  }
}

void LabApp::Script::choose_section(const Line& line) {
  if (const std::string problem = render::parse_section(line.argument, lab.section); !problem.empty())
    return fail(line, "section x|y|z[:WIDTH]|off: " + problem, 2);
}

void LabApp::Script::choose_camera(const Line& line) {
  const auto preset = render::parse_view_preset(line.argument);
  if (!preset) return fail(line, "camera front|side|top|three-quarter", 2);
  lab.preset_ = *preset;
  lab.fit_view();
}

void LabApp::Script::wait_for_frames(const Line& line) {
  if (const std::optional<double> n = number(line)) wait_frames = int(*n);
}

// ------------------------------------------------------------------ saving

void LabApp::Script::take_screenshot(const Line& line) { screenshot = line.argument; }

void LabApp::Script::save_frame(const Line& line) { lab.save_frame(line.argument); }

void LabApp::Script::save_checkpoint(const Line& line) {
  succeeded(line, experiment().save_checkpoint(line.argument));
}

void LabApp::Script::load_checkpoint(const Line& line) {
  succeeded(line, experiment().load_checkpoint(line.argument));
}

void LabApp::Script::export_results(const Line& line) {
  succeeded(line, experiment().export_results(line.argument));
}

void LabApp::Script::write_state(const Line& line) {
  write_file_atomic(line.argument, lab.state_text());
}

void LabApp::Script::quit(const Line&) { lab.quit_ = true; }

}  // namespace simsols
