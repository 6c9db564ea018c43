// Radius expansion (docs/specimens.md, "Radius expansion"): a specimen of
// spheres grown in place inside the closed cell, as PFC and YADE prepare
// dense or loose assemblies without pouring them.
//
// The scene's pour (its sizes, its random non-overlapping places in the
// pouring column) is the start: every radius and every height above the
// floor shrunk by kStartScale, which keeps the beads apart. Gravity is off
// while they grow, and the preparation's friction (else the materials')
// acts between them. Each growth step scales every radius by the same
// factor where the bead is (Simulation::scale_radii); the platen is a lid
// held at kExpansionStress over the cell by a proportional control from
// the host, coming down on the loose cloud and yielding as the packing
// grows into it. The rates follow an inertial number: I = kCloudInertia
// while the lid feels less than half its stress (the beads still a cloud),
// kGrowthInertia once they carry it, so the growth is quasi-static where
// it matters:
//   ds/dt = I sqrt(sigma / rho) / d50,   lid speed <= 4 I sqrt(sigma / rho) H / d50.
// At full size the specimen rests kRestTime under the lid, then becomes
// the scene's (`given`, gravity on): the test settles it and runs as for
// any other. The friction sets the density (frictionless: the densest;
// rough: loose), so a target void ratio or relative density is met by the
// preparation's friction search (preparation.h), each trial an expansion.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "solver/apparatus/specimen/prep_log.h"
#include "solver/core/cl_device.h"
#include "solver/scene/scene.h"

namespace simsols {

inline constexpr double kStartScale = 0.75;       // radii and heights at the start
inline constexpr double kExpansionStress = 10e3;  // Pa: the lid's push while the beads grow
inline constexpr double kCloudInertia = 0.05;
inline constexpr double kGrowthInertia = 1e-3;
inline constexpr double kRestTime = 0.01;         // s at full size before the test takes over

struct Expansion {
  Scene grown;           // the scene with its specimen `given`, full size, at rest
  double seconds = 0;    // simulated
  long long steps = 0;
  double lid_height = 0;  // m, where the lid held the grown specimen
  double lid_stress = 0;  // Pa, its push then
};

// Grows the scene's poured specimen of spheres (Preparation::expansion);
// `log` hears a progress line every 10 s of wall time.
Expansion expand_specimen(const Scene& scene, const std::shared_ptr<Device>& device,
                          const PrepLog& log);

}  // namespace simsols
