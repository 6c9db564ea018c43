// Expanding a scene's generators (Scene::generators) into particles.
//
// A generator is read from [[generators]] (solver/io) as a description;
// here it becomes spheres, once, when the scene is placed (place_scene,
// solver/io/scene_toml.h). Lattice sites are cubic or FCC close-packed
// layers (ABC stacking along z); a random fill is random sequential
// insertion without overlap, also clear of the particles before it.
// Deterministic on every platform: mt19937_64 is fully specified and the
// mapping to [0, 1) is ours (53 high bits).
//
// The generated spheres go where the file's order puts them: after the
// explicit [[particles]], before the member spheres of [[clumps]], each
// generator after the one before it; the clumps' member ranges move up.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

// Most particles one generator may create (guards against typos such as a
// box in millimetres with a radius in metres, or the reverse).
inline constexpr std::int64_t kMaxGenerated = 10'000'000;

// Cubic-lattice site count of a lattice generator (an FCC lattice has at
// most ~1.5 times more): a reader refuses absurd boxes before expanding.
double estimated_lattice_sites(const Generator& g);

// Expands scene.generators into particles and empties the list. On success
// `generator_of` (when given) holds, for each generated particle in order,
// its generator; the first generated particle is at `*first` (when given).
// A generator that cannot be met (too many lattice sites, the random fill's
// attempts exhausted) is an issue at its field ("generators[1].count"),
// the scene then left unchanged.
std::optional<SceneIssue> expand_generators(Scene& scene, std::vector<size_t>* generator_of = nullptr,
                                            size_t* first = nullptr);

}  // namespace simsols
