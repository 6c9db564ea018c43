// Checkpoints: the complete dynamic state of a run, so that a resumed run
// continues bit for bit as if it had never stopped (same device, same
// precision).
//
// File layout (little endian): "SIMSOLS-CKPT" magic, format version, the
// scene as exact TOML (to_toml), step, list builds, next list check, late
// builds, neighbour capacity, then
// every dynamic buffer as (name, byte count, bytes), then the driver's `extra`. Files are written to a
// temporary name and renamed, so a crash never leaves half a checkpoint.
#pragma once

#include <memory>
#include <string>

#include "simulation.h"

namespace simsols {

// `extra`: the state of whatever drives the run (e.g. the shear test's
// loading program), stored verbatim and handed back by load_checkpoint.
void save_checkpoint(Simulation& sim, const std::string& path, const std::string& extra = {});

// Rebuilds the simulation from a checkpoint. Throws SceneError (bad or
// foreign file, named with its path) or DeviceError.
std::unique_ptr<Simulation> load_checkpoint(std::shared_ptr<Device> device,
                                            const std::string& path,
                                            std::string* extra = nullptr);

}  // namespace simsols
