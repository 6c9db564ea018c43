// The errors of SimSols, one type for each kind of failure, so a caller (and
// the exit status) can tell what failed:
//
//   UsageError   a command-line flag or argument         exit 2
//   SceneError   a scene, profile, checkpoint or other    exit 2
//                file the user handed in
//   ReadError    a file read back or handed in that is    exit 2
//                malformed (rows, a summary, a checkpoint's
//                state, a mesh, a PNG), from code that does not
//                know the file's role; callers that do rethrow
//                it as a SceneError naming file and field
//   IoError      a file that could not be written        exit 5
//   DeviceError  the OpenCL runtime or a kernel build    exit 3
//   RunawayError (core/guard.h) the run blew up           exit 4
//
// A fault of the program itself throws std::logic_error (or a standard
// exception from the library): main reports it as an internal error, exit
// 70, never as a device failure. A library function's precondition on its
// arguments throws std::invalid_argument; the readers that take those
// arguments from a file check them first or rethrow as SceneError.
// tests/layout/check_errors.sh keeps the generic std::runtime_error out.
//
// UsageError and SceneError are InputErrors: they always name where the
// problem is (file or "command line", line when known, field as a dotted
// TOML path such as "materials[0].poisson_ratio" or the flag, "--sizes") and
// what would be accepted. `code` is a short stable identifier (e.g.
// "out_of_range", "unknown_key") so tests and tools can tell errors apart
// without parsing the message.
//
// One pass over a file may find several problems (every unknown key, every
// value out of range): one InputError then carries them all in `problems`,
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

struct InputError : std::runtime_error {
  InputError(std::string code, std::string file, int line, std::string field,
             const std::string& what)
      : InputError(std::move(file), {{std::move(code), line, std::move(field), what}}) {}

  // Every problem found in `file`, in the order found (at least one).
  InputError(std::string file, std::vector<SceneProblem> all)
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

// A problem in a file the user handed in: a scene, a display profile, a
// checkpoint, a study's state or results.
struct SceneError : InputError {
  using InputError::InputError;
};

// A problem with a command-line flag or argument; `file` is "command line"
// (or empty when an argument is missing altogether).
struct UsageError : InputError {
  using InputError::InputError;
  UsageError(std::string code, std::string flag, const std::string& what)
      : InputError(std::move(code), "command line", 0, std::move(flag), what) {}
};

// Failures of the OpenCL runtime or of a kernel build (with its build log).
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A file that could not be read as what it should be: `what()` says which
// row, field or key; the caller that knows the file's path and role usually
// rethrows it as a SceneError.
struct ReadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A file that could not be written (a missing folder, permissions, a full
// disk). Whatever was being written is left under its temporary name or
// removed; the previous file of that name is untouched.
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace simsols
