// Errors raised while turning user input into a Scene.
//
// A SceneError always names where the problem is (file, line when known,
// field as a dotted TOML path such as "materials[0].poisson_ratio") and what
// would be accepted. `code` is a short stable identifier (e.g. "out_of_range",
// "unknown_key") so tests and tools can tell errors apart without parsing the
// message.
#pragma once

#include <stdexcept>
#include <string>

namespace simsols {

struct SceneError : std::runtime_error {
  SceneError(std::string code, std::string file, int line, std::string field,
             const std::string& what)
      : std::runtime_error(format(file, line, field, what)),
        code(std::move(code)), file(std::move(file)), line(line),
        field(std::move(field)) {}

  std::string code;
  std::string file;
  int line = 0;  // 0 when unknown
  std::string field;

 private:
  static std::string format(const std::string& file, int line, const std::string& field,
                            const std::string& what) {
    std::string s = file.empty() ? std::string("<scene>") : file;
    if (line > 0) s += ":" + std::to_string(line);
    if (!field.empty()) s += ": field '" + field + "'";
    return s + ": " + what;
  }
};

// Failures of the OpenCL runtime or of a kernel build (with its build log).
struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace simsols
