// The script runner, private to LabApp: its state and its commands.
// lab_script.cpp runs one line per frame and looks its command up in
// kCommands; lab_script_commands.cpp holds the handlers, one per command,
// each parsing its own argument.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/lab/lab_app.h"

namespace simsols {

struct LabApp::Script {
  explicit Script(LabApp& lab) : lab(lab) {}

  LabApp& lab;
  std::string file;
  std::vector<std::pair<int, std::string>> lines;  // (line number, command)
  std::size_t next = 0;
  int wait_frames = 0;
  std::function<bool()> until;  // the running command's end condition
  std::string screenshot;       // taken at the end of this frame

  // One line as it runs: the command, its argument, and "FILE:LINE: " for
  // messages.
  struct Line {
    std::string command, argument, where;
  };
  // A command: its name and arguments, as the message for an unknown
  // command lists them, and the handler that runs it.
  struct Command {
    const char* name;
    const char* arguments;
    void (Script::*run)(const Line&);
  };
  static const Command kCommands[];  // lab_script.cpp, in docs/lab.md's order
  static std::string unknown_command(const std::string& command);  // lists kCommands

  bool still_waiting();  // on the last command's end condition, or on `frames`
  void run_next_line();

  // Ending the script: prints "FILE:LINE: what", the lab exits with `status`.
  void fail(const Line& line, const std::string& what, int status);
  // An action's error ends the script (status 1); true when there was none.
  bool succeeded(const Line& line, const std::string& error);
  // The argument as a number; ends the script (status 2) when it is not one.
  std::optional<double> number(const Line& line);
  LabExperiment& experiment() { return *lab.exp_; }

  // The commands (lab_script_commands.cpp), as docs/lab.md lists them.
  void choose_apparatus(const Line& line);     // apparatus KIND (a name of the registry)
  void choose_preset(const Line& line);        // preset D_MM S_KPA
  void open_scene(const Line& line);           // open SCENE.toml
  void use_material(const Line& line);         // material CALIBRATED.toml [TARGET]
  void choose_precision(const Line& line);     // precision float|double
  void choose_profile(const Line& line);       // profile paper|fast
  void choose_build(const Line& line);         // choose cell membrane (the next prepare's)
  void choose_effect(const Line& line);        // effect SLOT CHOICE
  void prepare(const Line& line);              // prepare
  void apply_load(const Line& line);           // load [KPA]
  void start(const Line& line);                // start
  void run_rows(const Line& line);             // rows N
  void run_steps(const Line& line);            // steps N
  void finish(const Line& line);               // finish
  void set_stress(const Line& line);           // set_stress KPA
  void set_speed(const Line& line);            // set_speed MM_S
  void set_rate(const Line& line);             // set_rate PER_S
  void set_setting(const Line& line, const char* key);  // the three above
  void pause(const Line& line);                // pause
  void resume(const Line& line);               // resume
  void step(const Line& line);                 // step
  void choose_view(const Line& line);          // view opaque|transparent|...
  void choose_color(const Line& line);         // color size|layer|...
  void choose_section(const Line& line);       // section x|y|z[:WIDTH]|off
  void choose_camera(const Line& line);        // camera front|side|top|three-quarter
  void wait_for_frames(const Line& line);      // frames N
  void take_screenshot(const Line& line);      // screenshot FILE.png
  void save_frame(const Line& line);           // frame FILE.png
  void save_checkpoint(const Line& line);      // checkpoint FILE
  void load_checkpoint(const Line& line);      // load_checkpoint FILE
  void export_results(const Line& line);       // export DIR
  void write_state(const Line& line);          // state FILE
  void quit(const Line& line);                 // quit
};

}  // namespace simsols
