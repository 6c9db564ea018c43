#include "app/experiment/run_cost.h"

#include <unistd.h>

#include <cstdio>

#include "solver/io/scene_toml.h"

namespace simsols {

std::string human_seconds(double s) {
  char buf[32];
  if (s < 90) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 5400) std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else if (s < 2 * 86400) std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  else std::snprintf(buf, sizeof buf, "%.1f days", s / 86400);
  return buf;
}

std::string human_bytes(double b) {
  char buf[32];
  if (b < 1e6) std::snprintf(buf, sizeof buf, "%.0f kB", b / 1e3);
  else if (b < 1e9) std::snprintf(buf, sizeof buf, "%.0f MB", b / 1e6);
  else std::snprintf(buf, sizeof buf, "%.1f GB", b / 1e9);
  return buf;
}

RunCost run_cost(Simulation& sim, double steps) {
  RunCost c;
  c.particles = sim.model().particles();
  c.steps = steps;
  c.device_bytes = double(sim.state().device_bytes() + sim.model().device_bytes() +
                          sim.guard().backup_bytes());
  double buffers = 0;
  for (auto& [name, buf] : sim.state().dynamic_buffers()) buffers += double(buf->bytes);
  c.checkpoint_bytes = buffers + double(to_toml(sim.scene()).size());
  c.seconds = c.particles * steps / kAssumedRate;
  return c;
}

void print_cost(const std::string& label, const RunCost& c) {
  std::fprintf(stderr,
               "[%s] cost: %d particles, ~%.3g steps, ~%s at %.0e particle-steps/s (refined once "
               "running), device memory %s, checkpoint %s\n",
               label.c_str(), c.particles, c.steps, human_seconds(c.seconds).c_str(), kAssumedRate,
               human_bytes(c.device_bytes).c_str(), human_bytes(c.checkpoint_bytes).c_str());
  const double ram = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (ram > 0 && c.device_bytes + c.checkpoint_bytes > ram)
    std::fprintf(stderr, "[%s] warning: this run needs about %s, more than this machine's %s\n",
                 label.c_str(), human_bytes(c.device_bytes + c.checkpoint_bytes).c_str(),
                 human_bytes(ram).c_str());
  if (c.seconds > 3600)
    std::fprintf(stderr,
                 "[%s] warning: about %s on this kind of machine; Ctrl-C stops it with a "
                 "checkpoint, --resume continues\n",
                 label.c_str(), human_seconds(c.seconds).c_str());
}

}  // namespace simsols
