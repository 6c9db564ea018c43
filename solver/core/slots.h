// Effect slots as compiled: what make_kernel_config() made of a scene's
// [effects] choices, in words.
//
// The model is a set of named slots (scene.h, Effects), each with a `none`
// choice. A slot is compiled in when the scene chooses something other than
// none and some material pair gives it a non-zero coefficient; each compiled
// sub-model declares its per-contact history (KernelConfig::history_planes).
// This file only describes: `simsols run --explain`, the lab's status line
// and `simsols bench --effects` print from it.
#pragma once

#include <string>
#include <vector>

#include "solver/core/cl_program.h"
#include "solver/scene/scene.h"

namespace simsols {

struct SlotReport {
  std::string slot;      // "damping", "tangential", ...
  std::string chosen;    // the scene's choice ("viscous", "none", ...)
  bool compiled = false; // code present in the kernels
  std::string why;       // when chosen but not compiled: the reason
  int history_reals = 0; // per contact (list slot and wall slot)
};

std::vector<SlotReport> slot_reports(const Scene& scene, const KernelConfig& config);

// One line: "normal=hertz damping=viscous tangential=mindlin ... history 16 B/contact".
std::string compiled_slots_line(const Scene& scene, const KernelConfig& config);

// The full explanation printed by `simsols run --explain`.
std::string explain_effects(const Scene& scene, const KernelConfig& config);

}  // namespace simsols
