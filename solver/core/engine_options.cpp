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

// The whole number `name` holds if `allowed` accepts it, else a UsageError
// naming the variable and `allowed_text`; unset, `fallback`.
int allowed_number(const char* name, int fallback, bool (*allowed)(int), const char* allowed_text) {
  const std::string text = variable(name);
  if (text.empty()) return fallback;
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !allowed(v))
    throw UsageError("out_of_range", "environment", 0, name,
                     "'" + text + "': allowed " + allowed_text);
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
  o.lanes = allowed_number("SIMSOLS_LANES", o.lanes, allowed_lanes, "1, 2, 4, 8 or 16");
  o.prefetch = on_off("SIMSOLS_PREFETCH", o.prefetch);
  o.huge_pages = on_off("SIMSOLS_HUGE_PAGES", o.huge_pages);
  o.local_size = allowed_number("SIMSOLS_LOCAL_SIZE", o.local_size, allowed_local_size,
                                "a power of two from 1 to 1024");
  return o;
}

}  // namespace simsols
