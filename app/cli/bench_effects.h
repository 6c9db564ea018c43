// simsols bench --effects: what each effect slot costs. The benchmark
// packing (cmd_bench.cpp) is run with the paper's slots (damping, Mindlin,
// constant rolling torque, gravity), then with each of them set to none,
// with each optional slot added (spring-dashpot rolling, capillary
// cohesion, fluid drag) and with every optional slot off (Hertz only).
// Printed per case: time per step, particle-steps per second, the
// per-contact history the kernels carry and the device bytes per particle.
#pragma once

#include <string>
#include <vector>

namespace simsols {

struct EffectsBenchOptions {
  std::vector<int> sizes{50000};
  std::vector<std::string> precisions{"float"};
  bool fcc = false;
  double budget = 3e7;
  int repeat = 5;
};

int bench_effects(const EffectsBenchOptions& opt);

}  // namespace simsols
