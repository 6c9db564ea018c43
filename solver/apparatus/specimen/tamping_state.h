// Where a layered tamping stands between two layers, kept in the run's
// folder (tamping_state.txt) so that a preparation stopped by Ctrl-C, or
// killed, goes on from the last layer it finished when the same command
// runs again, and ends as if it had not stopped, bit for bit.
//
// Between layers the specimen is rebuilt at rest from the grains'
// positions alone (tamping.h: velocities zero, contact history afresh), so
// the layers done, the grains where they lie and the running sums are the
// whole state. Every number is written in its shortest round-trip text, so
// reading it back gives the same bits. A state is tied to what is tamped
// (a key over the scene's name, its file's text, its materials, the poured
// column, the layers and the void ratio); one of another tamping is not
// used (the tamping starts afresh). The file is replaced
// atomically after each layer and removed when the tamping ends.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "solver/apparatus/specimen/tamping.h"
#include "solver/scene/scene.h"

namespace simsols {

inline constexpr const char* kTampingStateFile = "tamping_state.txt";

struct TampingState {
  std::uint64_t key = 0;           // tamping_key of what is tamped
  double floor = 0;                // m, the highest grain's top so far
  double solid_total = 0;          // m^3 of the layers so far
  std::vector<TampedLayer> layers; // the layers done, lowest first
  std::vector<double> seconds;     // wall time of each (for the ETA)
  std::vector<Clump> clumps;       // the grains at rest: clumps in the grains' frame,
  std::vector<Particle> spheres;   //   then the free spheres
};

// The key of tamping `scene` (placed, before tamping) to `void_ratio`.
std::uint64_t tamping_key(const Scene& scene, double void_ratio);

void save_tamping_state(const std::filesystem::path& file, const TampingState& state);
// The state in `file` when it exists and has `key`; nullopt when it does
// not exist or is of another tamping; ReadError naming the file when it is
// malformed.
std::optional<TampingState> load_tamping_state(const std::filesystem::path& file,
                                               std::uint64_t key);

}  // namespace simsols
