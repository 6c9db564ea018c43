// Problems found in a user's file (a scene, a display profile), described
// the same way for every format: one problem as "FILE:LINE: field 'F':
// what", several as "FILE: N problems:" and one indented line each, so a
// message names the file once.
#pragma once

#include <string>
#include <vector>

namespace simsols {

struct FileProblem {
  std::string code;  // a stable identifier ("unknown_key"); may be empty
  int line = 0;      // 0 when unknown
  std::string field;  // dotted path ("display.phase"); may be empty
  std::string message;  // what is wrong and what is allowed, without the place
};

// `file` empty reads "<scene>".
std::string describe_problems(const std::string& file, const std::vector<FileProblem>& all);

}  // namespace simsols
