// Flags and the environment, read at the edge (commands.h).
#include <cstdlib>

#include "app/cli/commands.h"
#include "render/view/frames.h"
#include "solver/common/errors.h"
#include "solver/core/cl_device.h"
#include "solver/core/engine_options.h"
#include "solver/scene/choices.h"

namespace simsols {

std::shared_ptr<Device> open_command_device() {
  return Device::open(engine_options_from_environment());
}

std::optional<Precision> precision_flag(const std::string& value, const std::string& flag) {
  if (value.empty()) return std::nullopt;
  if (auto p = parse_choice<Precision>(value)) return p;
  std::string allowed;
  for (const std::string& n : choice_names<Precision>()) allowed += (allowed.empty() ? "" : ", ") + n;
  throw UsageError("bad_enum", flag, "'" + value + "' is not one of: " + allowed);
}

void gl_from_environment(std::string& gl, bool given) {
  const char* v = std::getenv("SIMSOLS_GL");
  if (v && *v && !given) gl = v;
}

void gl_from_environment(FrameFlags& flags) { gl_from_environment(flags.gl, flags.given("--gl")); }

}  // namespace simsols
