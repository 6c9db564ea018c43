#include "solver/core/engine_options.h"

#include <cstdlib>
#include <string>

#include "solver/common/errors.h"

namespace simsols {
namespace {

std::string variable(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

// A whole positive number, or a UsageError naming the variable.
int positive(const char* name, const std::string& text, const char* allowed) {
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || v < 1)
    throw UsageError("out_of_range", "environment", 0, name, "'" + text + "': allowed " + allowed);
  return v;
}

// "1" (on) or "0" (off), else a UsageError naming the variable; unset,
// `fallback`.
bool on_off(const char* name, bool fallback) {
  const std::string text = variable(name);
  if (text.empty()) return fallback;
  if (text != "0" && text != "1")
    throw UsageError("out_of_range", "environment", 0, name,
                     "'" + text + "': allowed 0 (off) or 1 (on, the default)");
  return text == "1";
}

}  // namespace

EngineOptions engine_options_from_environment() {
  EngineOptions o;
  o.device = variable("SIMSOLS_CL_DEVICE");
  o.cl_options = variable("SIMSOLS_CL_OPTIONS");
  if (const std::string l = variable("SIMSOLS_LANES"); !l.empty()) {
    o.lanes = positive("SIMSOLS_LANES", l, "1, 2, 4, 8 or 16");
    if (!allowed_lanes(o.lanes))
      throw UsageError("out_of_range", "environment", 0, "SIMSOLS_LANES",
                       "'" + l + "': allowed 1, 2, 4, 8 or 16");
  }
  o.prefetch = on_off("SIMSOLS_PREFETCH", o.prefetch);
  o.huge_pages = on_off("SIMSOLS_HUGE_PAGES", o.huge_pages);
  if (const std::string s = variable("SIMSOLS_LOCAL_SIZE"); !s.empty()) {
    o.local_size = positive("SIMSOLS_LOCAL_SIZE", s, "a power of two from 1 to 1024");
    if (!allowed_local_size(o.local_size))
      throw UsageError("out_of_range", "environment", 0, "SIMSOLS_LOCAL_SIZE",
                       "'" + s + "': allowed a power of two from 1 to 1024");
  }
  return o;
}

}  // namespace simsols
