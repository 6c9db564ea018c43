// The script runner's state, private to LabApp (lab_script.cpp).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "app/lab/lab_app.h"

namespace simsols {

struct LabApp::Script {
  std::string file;
  std::vector<std::pair<int, std::string>> lines;  // (line number, command)
  std::size_t next = 0;
  int wait_frames = 0;
  std::function<bool()> until;  // the running command's end condition
  std::string screenshot;       // taken at the end of this frame
};

}  // namespace simsols
