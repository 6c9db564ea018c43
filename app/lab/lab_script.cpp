// Scripts for the lab (`simsols lab --script FILE`): one command per line,
// run in order, one per frame, while the window keeps drawing. Commands
// that start something wait until it is there. '#' starts a comment.
//
//   preset D_MM S_KPA     choose a Table 1 preset, e.g. preset 4.76 280 (then `prepare`)
//   open SCENE.toml       choose a scene file
//   precision float|double
//   effect SLOT CHOICE    an effect slot's model (damping viscous; applies at the next prepare)
//   prepare               build the specimen; waits until it is built
//   load                  apply the normal stress; waits until consolidated
//   start                 start shearing (then paused: continue with rows, steps or resume)
//   rows N                run until N rows are measured, then pause exactly there
//   steps N               run N more steps, then pause exactly there
//   set_stress KPA        new target normal stress (the servo follows)
//   set_speed MM_S        new shear speed
//   pause | resume | step
//   view opaque|transparent|chains|alioscopy|grid|single
//   color size|layer|speed|displacement|contacts|rotation
//   camera front|side|top|three-quarter
//   frames N              wait N frames
//   screenshot FILE.png   the whole window, as drawn this frame
//   frame FILE.png        the viewport only (or the Alioscopy image)
//   checkpoint FILE       save a checkpoint of the running experiment
//   load_checkpoint FILE  continue from a checkpoint
//   export DIR            shear.csv, summary.txt, plots
//   state FILE            the experiment's state as key = value lines
//   quit
// kCommands below lists the same commands for messages: keep both in step.
// A failing command prints "FILE:LINE: message" and ends the lab with
// status 1 (2 for an unknown command or a bad argument).
#define GLFW_INCLUDE_NONE  // GL comes from render/gl/gl_api.h
#include <GLFW/glfw3.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

#include "solver/common/did_you_mean.h"
#include "solver/scene/choices.h"
#include "app/lab/lab_script.h"
#include "solver/io/output.h"
#include "app/experiment/paper_tests.h"
#include "solver/core/slots.h"

namespace simsols {

bool LabApp::script_pending_screenshot() const { return script_ && !script_->screenshot.empty(); }

void LabApp::take_script_screenshot() {
  save_screenshot(script_->screenshot);
  script_->screenshot.clear();
}

namespace {

// Sets slot `slot` of `e` to the choice named `choice` (the scene file's
// names, slot_name); false when either is unknown.
template <typename E>
bool pick(E& field, const std::string& choice, std::initializer_list<E> all) {
  for (E c : all)
    if (choice == choice_name(c)) return field = c, true;
  return false;
}

// The commands and their arguments, as the header above lists them: the
// message for an unknown command lists them.
const std::pair<const char*, const char*> kCommands[] = {
    {"preset", "D_MM S_KPA"},
    {"open", "SCENE.toml"},
    {"precision", "float|double"},
    {"effect", "SLOT CHOICE"},
    {"prepare", ""},
    {"load", ""},
    {"start", ""},
    {"rows", "N"},
    {"steps", "N"},
    {"set_stress", "KPA"},
    {"set_speed", "MM_S"},
    {"pause", ""},
    {"resume", ""},
    {"step", ""},
    {"view", "opaque|transparent|chains|alioscopy|grid|single"},
    {"color", "size|layer|speed|displacement|contacts|rotation"},
    {"camera", "front|side|top|three-quarter"},
    {"frames", "N"},
    {"screenshot", "FILE.png"},
    {"frame", "FILE.png"},
    {"checkpoint", "FILE"},
    {"load_checkpoint", "FILE"},
    {"export", "DIR"},
    {"state", "FILE"},
    {"quit", ""},
};

std::string unknown_command(const std::string& cmd) {
  std::vector<std::string> names;
  std::string list;
  for (const auto& [name, args] : kCommands) {
    names.push_back(name);
    list += "\n  " + std::string(name) + (*args ? " " + std::string(args) : "");
  }
  return "unknown command '" + cmd + "'" + did_you_mean(cmd, names) + "; the commands:" + list;
}

// "damping none|viscous; tangential none|mindlin; ...": what `effect` takes.
std::string effect_choices() {
  auto names = [](auto... c) {
    std::string s;
    ((s += (s.empty() ? "" : "|") + std::string(choice_name(c))), ...);
    return s;
  };
  using R = RollingModel;
  return "damping " + names(DampingModel::None, DampingModel::Viscous) + "; tangential " +
         names(TangentialModel::None, TangentialModel::Mindlin) + "; rolling " +
         names(R::None, R::ConstantTorque, R::SpringDashpot) + "; cohesion " +
         names(CohesionModel::None, CohesionModel::Capillary) + "; fluid " +
         names(FluidModel::None, FluidModel::Drag);
}

bool set_slot(Effects& e, const std::string& slot, const std::string& choice) {
  using D = DampingModel;
  using T = TangentialModel;
  using R = RollingModel;
  using C = CohesionModel;
  using F = FluidModel;
  if (slot == "damping") return pick(e.damping, choice, {D::None, D::Viscous});
  if (slot == "tangential") return pick(e.tangential, choice, {T::None, T::Mindlin});
  if (slot == "rolling")
    return pick(e.rolling, choice, {R::None, R::ConstantTorque, R::SpringDashpot});
  if (slot == "cohesion") return pick(e.cohesion, choice, {C::None, C::Capillary});
  if (slot == "fluid") return pick(e.fluid, choice, {F::None, F::Drag});
  return false;
}

}  // namespace

std::string LabApp::state_text() {
  std::ostringstream o;
  o.precision(10);
  Simulation* sim = exp_->simulation();
  ShearTest* t = exp_->test();
  o << "stage = " << to_string(exp_->stage()) << "\n";
  o << "paused = " << (exp_->paused() ? 1 : 0) << "\n";
  if (sim) {
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sim->hash()));
    o << "steps = " << sim->steps() << "\ntime_s = " << sim->time() << "\nbeads = "
      << sim->model().particles() << "\nhash = " << hash << "\n";
    // what the status line shows: the effect slots compiled into the kernels
    o << "compiled = " << compiled_slots_line(sim->scene(), sim->model().config())
      << "\nhistory_bytes = " << sim->model().config().history_bytes_per_contact() << "\n";
  }
  if (t) {
    o << "rows = " << t->rows().size() << "\n";
    o << "sigma_target_kpa = " << t->normal_stress() * 1e-3 << "\n";
    o << "shear_speed_mm_s = " << t->shear_speed() * 1e3 << "\n";
    if (!t->rows().empty()) {
      const ShearRow& r = t->rows().back();
      o << "displacement_mm = " << r.displacement * 1e3 << "\nsigma_kpa = " << r.sigma * 1e-3
        << "\ntau_kpa = " << r.tau * 1e-3 << "\ninertial_number = " << r.inertial_number
        << "\n";
    }
  }
  o << "fps = " << fps_ << "\nrender_scale = " << render_scale_ << "\n";
  return o.str();
}

void LabApp::run_script() {
  Script& s = *script_;
  if (s.wait_frames > 0) {
    --s.wait_frames;
    return;
  }
  if (s.until && !s.until()) return;
  s.until = nullptr;
  if (s.next >= s.lines.size()) {
    quit_ = true;
    return;
  }
  const auto [line_no, text] = s.lines[s.next++];
  std::istringstream in(text);
  std::string cmd, arg;
  in >> cmd;
  std::getline(in >> std::ws, arg);
  const std::string where = s.file + ":" + std::to_string(line_no) + ": ";
  auto fail = [&](const std::string& what, int status) {
    std::fprintf(stderr, "%s%s\n", where.c_str(), what.c_str());
    exit_status_ = status;
    quit_ = true;
  };
  auto check = [&](const std::string& err) {
    if (!err.empty()) fail(err, 1);
    return err.empty();
  };
  auto number = [&](double& v) {
    char* end = nullptr;
    v = std::strtod(arg.c_str(), &end);
    if (arg.empty() || *end) {
      fail("'" + cmd + "' needs a number, got '" + arg + "'", 2);
      return false;
    }
    return true;
  };
  double v = 0;
  std::printf("[script] %s\n", text.c_str());
  std::fflush(stdout);
  if (cmd == "preset") {
    double d = 0, kpa = 0;
    if (std::sscanf(arg.c_str(), "%lf %lf", &d, &kpa) != 2) return fail("preset D_MM S_KPA", 2);
    if (check(exp_->load_preset(d, kpa))) {
      sigma_kpa_ = float(kpa);
      const double size = nearest_table1_size(d).value_or(d);
      for (int k = 0; k < 5; ++k)  // the panel's combo boxes follow
        if (kTable1SizesMm[k] == size) preset_size_ = k;
      for (int k = 0; k < 4; ++k)
        if (std::fabs(kPaperStressesKpa[k] - kpa) < 1e-9) preset_stress_ = k;
    }
  } else if (cmd == "open") {
    check(exp_->load_scene_file(arg));
  } else if (cmd == "precision") {
    if (arg != "float" && arg != "double") return fail("precision float|double", 2);
    exp_->set_precision(arg == "float" ? Precision::Float : Precision::Double);
  } else if (cmd == "effect") {
    // the panel's slot choices: effect SLOT CHOICE (applies at the next prepare)
    char slot[32] = {0}, choice[32] = {0};
    if (std::sscanf(arg.c_str(), "%31s %31s", slot, choice) != 2)
      return fail("effect SLOT CHOICE, one of: " + effect_choices(), 2);
    Effects e = exp_->scene().effects;
    if (!set_slot(e, slot, choice))
      return fail("effect " + arg + ": unknown slot or choice; allowed: " + effect_choices(), 2);
    exp_->set_effects(e);
  } else if (cmd == "prepare") {
    if (check(exp_->prepare())) s.until = [this] { return exp_->stage() == LabStage::Prepared; };
  } else if (cmd == "load") {
    if (check(exp_->apply_normal_stress()))
      s.until = [this] { return exp_->stage() == LabStage::Loaded; };
  } else if (cmd == "start") {
    // shearing starts at once from Loaded; scripts then move on with `rows`
    // or `steps` (paused until then, so a session is the same every time)
    if (check(exp_->start_shear())) {
      exp_->pause();
      s.until = [this] { return exp_->stage() == LabStage::Shearing || exp_->stage() == LabStage::Done; };
    }
  } else if (cmd == "rows") {
    if (!number(v)) return;
    const std::size_t n = std::size_t(v);
    exp_->pause_at(n, 0);
    exp_->resume();
    s.until = [this, n] {
      return !exp_->test() || exp_->test()->done() ||
             (exp_->test()->rows().size() >= n && exp_->paused());
    };
  } else if (cmd == "steps") {
    if (!number(v) || !exp_->simulation()) return;
    const std::int64_t target = exp_->simulation()->steps() + std::int64_t(v);
    exp_->pause_at(0, target);
    exp_->resume();
    s.until = [this, target] {
      return !exp_->simulation() || (exp_->simulation()->steps() >= target && exp_->paused());
    };
  } else if (cmd == "set_stress") {
    if (number(v) && check(exp_->set_normal_stress(v * 1e3))) sigma_kpa_ = float(v);
  } else if (cmd == "set_speed") {
    if (number(v)) check(exp_->set_shear_speed(v * 1e-3));
  } else if (cmd == "pause") {
    exp_->pause();
  } else if (cmd == "resume") {
    exp_->resume();
  } else if (cmd == "step") {
    check(exp_->step());
  } else if (cmd == "view") {
    const std::pair<const char*, LabView> views[] = {
        {"opaque", LabView::Opaque},       {"transparent", LabView::Transparent},
        {"chains", LabView::Chains},       {"alioscopy", LabView::Alioscopy},
        {"grid", LabView::Grid},           {"single", LabView::Single}};
    bool found = false;
    for (auto [name, lv] : views)
      if (arg == name) view = lv, found = true;
    if (!found) fail("view opaque|transparent|chains|alioscopy|grid|single", 2);
  } else if (cmd == "color") {
    if (auto f = parse_color_field(arg)) field = *f;
    else fail("color size|layer|speed|displacement|contacts|rotation", 2);
  } else if (cmd == "camera") {
    if (auto p = render::parse_view_preset(arg)) {
      preset_ = *p;
      fit_view();
    } else {
      fail("camera front|side|top|three-quarter", 2);
    }
  } else if (cmd == "frames") {
    if (number(v)) s.wait_frames = int(v);
  } else if (cmd == "screenshot") {
    s.screenshot = arg;
  } else if (cmd == "frame") {
    save_frame(arg);
  } else if (cmd == "checkpoint") {
    check(exp_->save_checkpoint(arg));
  } else if (cmd == "load_checkpoint") {
    check(exp_->load_checkpoint(arg));
  } else if (cmd == "export") {
    check(exp_->export_results(arg));
  } else if (cmd == "state") {
    write_file_atomic(arg, state_text());
  } else if (cmd == "quit") {
    quit_ = true;
  } else {
    fail(unknown_command(cmd), 2);
  }
}

}  // namespace simsols
