// Checkpoints: the complete dynamic state of a run, so that a resumed run
// continues bit for bit as if it had never stopped (same device, same
// precision).
//
// File layout (format version 8, little endian):
//   "SIMSOLS-CKPT"   12 bytes of magic
//   version          u32 (8)
//   payload bytes    u64
//   payload CRC-32   u32 (zlib's crc32 of the payload)
//   payload          the scene as exact TOML (to_toml), step, list builds,
//                    next list check, late builds, the allocated upper and
//                    lower neighbour-list slots and wall slots (three i32), every
//                    dynamic buffer as (name, byte count, bytes), the
//                    shares of the last step ("share", the pair forces the
//                    contact list and the force chains read), then the
//                    driver's `extra` (e.g. the shear test's loading program)
// The whole file is verified (size and checksum) before anything is built
// from it, so a damaged file is refused with the reason instead of
// resuming from garbage. Files of versions 5 to 7 load without shares
// (their pair forces are known after the next step); those of 5 and 6 have
// their history records (spring) regrouped by component, and version 5's
// one extra buffer, the lower slots' partner ids, is skipped. Files of versions 3 and 4 (fixed-capacity neighbour lists) are
// refused with that reason: rerun them from their scene.
//
// Files are written to a temporary name in the same folder and renamed, so
// a crash or a kill -9 never leaves half a checkpoint: the previous one
// stays loadable until the new one is complete.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "solver/core/simulation.h"

namespace simsols {

inline constexpr std::uint32_t kCheckpointVersion = 8;

// `extra`: the state of whatever drives the run (e.g. the shear test's
// loading program), stored verbatim and handed back by load_checkpoint.
void save_checkpoint(Simulation& sim, const std::string& path, const std::string& extra = {});

// Throws SceneError naming `path` unless it is a complete checkpoint whose
// size and checksum match (format version 5 to kCheckpointVersion). Reads the file
// once; builds nothing. Returns the format version.
std::uint32_t verify_checkpoint(const std::string& path);

// Rebuilds the simulation from a checkpoint (verified first). Throws
// SceneError (bad, damaged or foreign file, named with its path) or
// DeviceError.
std::unique_ptr<Simulation> load_checkpoint(std::shared_ptr<Device> device,
                                            const std::string& path,
                                            std::string* extra = nullptr);

}  // namespace simsols
