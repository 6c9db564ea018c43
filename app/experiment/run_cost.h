// What a run will cost, said before it starts: particles, steps, time,
// device memory and checkpoint size. The time is the steps at an assumed
// rate (kAssumedRate, this project's measured figure on a 2-core CPU,
// docs/performance.md) until the run has measured its own; the progress
// line then gives the ETA at the measured rate.
#pragma once

#include <string>

#include "solver/core/simulation.h"

namespace simsols {

inline constexpr double kAssumedRate = 1e7;  // particle-steps per second

struct RunCost {
  int particles = 0;
  double steps = 0;
  double device_bytes = 0;      // state, model and runaway guard
  double checkpoint_bytes = 0;  // one checkpoint file
  double seconds = 0;           // at kAssumedRate
};

RunCost run_cost(Simulation& sim, double steps);

// "[label] cost: 324 beads, ~3.8e5 steps, ~12 s at 1e7 particle-steps/s, ..."
// plus a warning line when the run needs more memory than the machine
// has, or more than an hour.
void print_cost(const std::string& label, const RunCost& cost);

// "12 s", "3.4 min", "2.1 h", "3.0 days"
std::string human_seconds(double seconds);
std::string human_bytes(double bytes);

}  // namespace simsols
