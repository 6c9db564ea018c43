#include "app/cli/bench_effects.h"

#include "app/cli/commands.h"
#include "solver/core/cl_device.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "solver/core/simulation.h"
#include "solver/core/slots.h"
#include "solver/scene/choices.h"

namespace simsols {

Scene bench_scene(int target, Precision precision, bool fcc);  // cmd_bench.cpp

namespace {

struct Case {
  const char* name;
  std::function<void(Effects&)> edit;
};

std::vector<Case> cases() {
  const double d = 2.38125e-3;
  return {
      {"paper slots (all on)", [](Effects&) {}},
      {"damping = none", [](Effects& e) { e.damping = DampingModel::None; }},
      {"tangential = none", [](Effects& e) { e.tangential = TangentialModel::None; }},
      {"rolling = none", [](Effects& e) { e.rolling = RollingModel::None; }},
      {"gravity = none", [](Effects& e) { e.gravity = {0, 0, 0}; }},
      {"rolling = spring_dashpot", [](Effects& e) { e.rolling = RollingModel::SpringDashpot; }},
      {"cohesion = capillary",
       [d](Effects& e) {
         e.cohesion = CohesionModel::Capillary;  // water, 1e-3 of a bead per bridge
         e.capillary = {0.072, 0, 1e-3 * std::numbers::pi / 6 * d * d * d};
       }},
      {"fluid = drag",
       [](Effects& e) {
         e.fluid = FluidModel::Drag;
         e.fluid_params = {1000, 1e-3, {0, 0, 0}};
       }},
      {"Hertz only (all none)",
       [](Effects& e) {
         e.damping = DampingModel::None;
         e.tangential = TangentialModel::None;
         e.rolling = RollingModel::None;
         e.gravity = {0, 0, 0};
       }},
  };
}

}  // namespace

int bench_effects(const EffectsBenchOptions& opt) {
  auto device = open_command_device();
  std::printf("device: %s\npacking: %s; median of %d\n", device->description().c_str(),
              opt.fcc ? "fcc" : "cubic", opt.repeat);
  std::printf("%-26s %9s %9s %12s %16s %10s %12s %11s\n", "case", "particles", "precision",
              "us/step", "particle-steps/s", "hist B/ct", "slot B/ct", "B/particle");
  for (const std::string& prec : opt.precisions) {
    const Precision p = *parse_choice<Precision>(prec);
    if (p == Precision::Double && !device->has_double()) continue;
    for (int n : opt.sizes) {
      for (const Case& c : cases()) {
        Scene s = bench_scene(n, p, opt.fcc);
        c.edit(s.effects);
        Simulation sim(device, s);
        sim.advance(5);
        device->finish();
        const auto steps = static_cast<std::int64_t>(std::clamp(opt.budget / n, 20.0, 5000.0));
        std::vector<double> sec;
        for (int r = 0; r < opt.repeat; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          sim.advance(steps);
          device->finish();
          sec.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() /
                        double(steps));
        }
        std::sort(sec.begin(), sec.end());
        const double t = sec[sec.size() / 2];
        const KernelConfig& k = sim.model().config();
        // bytes of one listed pair: ids and the previous id (upper slot),
        // id and mirror (lower slot), the shares, the history
        const size_t slot = 4 * sizeof(int) + 2 * 4 * k.real_size() + k.history_bytes_per_contact();
        std::printf("%-26s %9d %9s %12.2f %16.4g %10zu %12zu %11.0f\n", c.name, n, prec.c_str(),
                    t * 1e6, n / t, k.history_bytes_per_contact(), slot,
                    double(sim.state().device_bytes() + sim.model().device_bytes()) / n);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

}  // namespace simsols
