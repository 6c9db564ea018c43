// Oedometer: one-dimensional compression as walls, and its specimen.
//
// build_oedometer() is to an [oedometer] what build_shear_box() is to a
// [shear_box]: it places the specimen (specimen.h: layers, pour or given)
// in the square ring's footprint and appends six rectangle walls to
// Scene::walls: the floor, the ring's four sides and the top platen. The
// ring is square rather than round because the solver's walls are planes
// and rectangles; a square ring also measures the lateral stress on each
// side, so its two directions can be compared. The sides reach well above
// the specimen (the pour column and the platen's start); the platen starts
// a fifth of a diameter above the highest bead and is lowered onto the
// settled specimen by the loading programme (oedometer_programme.h).
// Automatic values (the wall material) are resolved into the Oedometer, so
// to_toml() writes a scene that rebuilds the same walls.
#pragma once

#include <optional>

#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

// Appends the apparatus (and the specimen) to `scene`; returns the first
// problem, with its field under "oedometer".
std::optional<SceneIssue> build_oedometer(Scene& scene);

// The time an oedometer test simulates (registry.h `expected_time`): a
// third of its settling allowance and of every load step's longest hold
// (each ends at equilibrium, usually sooner).
double oedometer_expected_time(const Scene& scene);

// Inside area of the ring (m^2).
double oedometer_area(const Oedometer& o);

// The load steps' branches: the index of the largest step (the last of the
// loading branch); the steps after it unload.
int oedometer_peak_step(const Oedometer& o);

}  // namespace simsols
