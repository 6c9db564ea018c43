// Errors raised while turning user input into a Scene.
//
// A SceneError always names where the problem is (file, line when known,
// field as a dotted TOML path such as "materials[0].poisson_ratio") and what
// would be accepted. `code` is a short stable identifier (e.g. "out_of_range",
// "unknown_key") so tests and tools can tell errors apart without parsing the
// message.
//
// One pass over a file may find several problems (every unknown key, every
// value out of range): one SceneError then carries them all in `problems`,
// code, line, field and message being the first's, and what() names the
// file once and lists them, one a line.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "solver/common/problems.h"

namespace simsols {

// One problem at one place of a file (common/problems.h).
using SceneProblem = FileProblem;

struct SceneError : std::runtime_error {
  SceneError(std::string code, std::string file, int line, std::string field,
             const std::string& what)
      : SceneError(std::move(file), {{std::move(code), line, std::move(field), what}}) {}

  // Every problem found in `file`, in the order found (at least one).
  SceneError(std::string file, std::vector<SceneProblem> all)
      : std::runtime_error(describe_problems(file, all)),
        code(all.at(0).code), file(std::move(file)), line(all[0].line), field(all[0].field),
        message(all[0].message), problems(std::move(all)) {}

  std::string code;
  std::string file;
  int line = 0;  // 0 when unknown
  std::string field;
  std::string message;                // the first problem's, without file and field
  std::vector<SceneProblem> problems;  // all of them, this one first
};

// Failures of the OpenCL runtime or of a kernel build (with its build log).
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace simsols
