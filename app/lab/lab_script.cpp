// Scripts for the lab (`simsols lab --script FILE`): one command per line,
// run in order, one per frame, while the window keeps drawing. Commands
// that start something wait until it is there. '#' starts a comment.
// kCommands below is the list of commands: each entry is a command's name,
// its arguments (the message for an unknown command lists them) and its
// handler (lab_script_commands.cpp). docs/lab.md, "Scripts", describes them.
// A failing command prints "FILE:LINE: message" and ends the lab with
// status 1 (2 for an unknown command or a bad argument).
#define GLFW_INCLUDE_NONE  // GL comes from render/gl/gl_api.h
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "solver/common/did_you_mean.h"
#include "app/lab/lab_script.h"
#include "solver/core/slots.h"
#include "solver/scene/choices.h"

namespace simsols {

bool LabApp::script_pending_screenshot() const { return script_ && !script_->screenshot.empty(); }

void LabApp::take_script_screenshot() {
  save_screenshot(script_->screenshot);
  script_->screenshot.clear();
}

// The commands, as docs/lab.md lists them. A new command is one entry here
// and its handler in lab_script_commands.cpp.
const LabApp::Script::Command LabApp::Script::kCommands[] = {
    {"apparatus", "shear_box|oedometer|triaxial", &Script::choose_apparatus},
    {"preset", "D_MM S_KPA", &Script::choose_preset},
    {"open", "SCENE.toml", &Script::open_scene},
    {"material", "CALIBRATED.toml [TARGET]", &Script::use_material},
    {"precision", "float|double", &Script::choose_precision},
    {"profile", "paper|fast", &Script::choose_profile},
    {"choose", "KEY OPTION", &Script::choose_build},
    {"effect", "SLOT CHOICE", &Script::choose_effect},
    {"prepare", "", &Script::prepare},
    {"load", "[KPA]", &Script::apply_load},
    {"start", "", &Script::start},
    {"rows", "N", &Script::run_rows},
    {"steps", "N", &Script::run_steps},
    {"finish", "", &Script::finish},
    {"set_stress", "KPA", &Script::set_stress},
    {"set_speed", "MM_S", &Script::set_speed},
    {"set_rate", "PER_S", &Script::set_rate},
    {"pause", "", &Script::pause},
    {"resume", "", &Script::resume},
    {"step", "", &Script::step},
    {"view", "opaque|transparent|chains|alioscopy|grid|single", &Script::choose_view},
    {"color", "size|layer|speed|displacement|contacts|rotation|grain|nonaffine", &Script::choose_color},
    {"section", "x|y|z[:WIDTH]|off", &Script::choose_section},
    {"camera", "front|side|top|three-quarter", &Script::choose_camera},
    {"frames", "N", &Script::wait_for_frames},
    {"screenshot", "FILE.png", &Script::take_screenshot},
    {"frame", "FILE.png", &Script::save_frame},
    {"checkpoint", "FILE", &Script::save_checkpoint},
    {"load_checkpoint", "FILE", &Script::load_checkpoint},
    {"export", "DIR", &Script::export_results},
    {"state", "FILE", &Script::write_state},
    {"quit", "", &Script::quit},
};

// "unknown command 'prset' (did you mean 'preset'?); the commands:" and
// one line per command with its arguments.
std::string LabApp::Script::unknown_command(const std::string& command) {
  std::vector<std::string> names;
  std::string list;
  for (const auto& [name, arguments, run] : kCommands) {
    names.push_back(name);
    list += "\n  " + std::string(name) + (*arguments ? " " + std::string(arguments) : "");
  }
  return "unknown command '" + command + "'" + did_you_mean(command, names) + "; the commands:" +
         list;
}

std::string LabApp::state_text() {
  std::ostringstream o;
  o.precision(10);
  Simulation* sim = exp_->simulation();
  LabApparatus* a = exp_->apparatus();
  o << "stage = " << exp_->stage_text() << "\n";
  if (a) o << "apparatus = " << a->kind() << "\n";
  o << "scene = " << exp_->scene_label() << "\n";  // the next prepare's
  if (const Specimen* s = exp_->scene().specimen()) {
    o << "specimen_method = " << choice_name(s->method) << "\n";
    if (s->preparation.friction) o << "preparation_friction = " << *s->preparation.friction << "\n";
  }
  for (const Material& m : exp_->scene().materials)
    o << "sliding_friction." << m.name << " = " << m.sliding_friction << "\nrolling_friction."
      << m.name << " = " << m.rolling_friction << "\n";
  o << "preparation_dir = " << exp_->preparation_dir() << "\n";
  o << "profile = " << exp_->profile() << "\n";
  o << "paused = " << (exp_->paused() ? 1 : 0) << "\n";
  o << "color = " << to_string(field) << "\nsection = " << render::section_text(section) << "\n";
  if (sim) {
    char hash[32];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(sim->hash()));
    o << "steps = " << sim->steps() << "\ntime_s = " << sim->time() << "\nbeads = "
      << sim->model().particles() << "\nhash = " << hash << "\ndt_s = " << sim->dt() << "\n";
    // what the status line shows: the effect slots compiled into the kernels
    o << "compiled = " << compiled_slots_line(sim->scene(), sim->model().config())
      << "\nhistory_bytes = " << sim->model().config().history_bytes_per_contact() << "\n";
  }
  if (a) o << a->state_lines();
  o << "fps = " << fps_ << "\nrender_scale = " << render_scale_ << "\ndraw_ms = " << draw_ms_
    << "\nsolver_steps_per_s = " << exp_->steps_per_second() << "\n";
  o << "live_plots = " << plots_shown_ << "\nlive_plot_height_px = " << plot_height_
    << "\nmeasured_points = " << measured_shown_ << "\n";
  return o.str();
}

void LabApp::run_script() {
  Script& s = *script_;
  if (s.still_waiting()) return;
  if (s.next >= s.lines.size()) {
    quit_ = true;
    return;
  }
  s.run_next_line();
}

bool LabApp::Script::still_waiting() {
  if (wait_frames > 0) {
    --wait_frames;
    return true;
  }
  if (until && !until()) return true;
  until = nullptr;
  return false;
}

void LabApp::Script::run_next_line() {
  const auto [line_no, text] = lines[next++];
  std::istringstream in(text);
  Line line;
  in >> line.command;
  std::getline(in >> std::ws, line.argument);
  line.where = file + ":" + std::to_string(line_no) + ": ";
  std::printf("[script] %s\n", text.c_str());
  std::fflush(stdout);
  for (const Command& c : kCommands)
    if (line.command == c.name) {
      (this->*c.run)(line);
      return;
    }
  fail(line, unknown_command(line.command), 2);
}

void LabApp::Script::fail(const Line& line, const std::string& what, int status) {
  std::fprintf(stderr, "%s%s\n", line.where.c_str(), what.c_str());
  lab.exit_status_ = status;
  lab.quit_ = true;
}

bool LabApp::Script::succeeded(const Line& line, const std::string& error) {
  if (!error.empty()) fail(line, error, 1);
  return error.empty();
}

std::optional<double> LabApp::Script::number(const Line& line) {
  const std::string& arg = line.argument;
  char* end = nullptr;
  const double v = std::strtod(arg.c_str(), &end);
  if (arg.empty() || *end) {
    fail(line, "'" + line.command + "' needs a number, got '" + arg + "'", 2);
    return std::nullopt;
  }
  return v;
}

}  // namespace simsols
