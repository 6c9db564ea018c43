#include "simulation.h"

#include <mutex>

namespace simsols {

Simulation::Simulation(std::shared_ptr<Device> device, const Scene& scene)
    : model_(std::make_unique<Model>(std::move(device), scene)),
      state_(std::make_unique<State>(*model_)) {}

void Simulation::advance(std::int64_t steps) {
  for (std::int64_t i = 0; i < steps; ++i) step(*model_, *state_);
}

std::shared_ptr<Device> default_device() {
  static std::mutex mutex;
  static std::shared_ptr<Device> device;
  std::lock_guard lock(mutex);
  if (!device) device = Device::open();
  return device;
}

}  // namespace simsols
