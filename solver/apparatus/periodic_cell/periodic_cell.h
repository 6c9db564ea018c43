// The periodic cell as an apparatus: its specimen placed from the scene's
// description, and what is measured in it.
//
// build_periodic_cell() is to a [periodic_cell] what build_shear_box() is
// to a [shear_box]: it fills a cube with a random gas (random sequential
// insertion, generators.h) at the description's solid fraction and sets
// Scene::periodic to that cube; it adds no walls, switches gravity off and
// keeps a given specimen (a resolved scene) as it is.
//
// measure_cell() reads the contact forces and averages them over the cell
// (Love-Weber, as stress.h, with each branch vector the nearest image of
// the partner): the mean stress carried by the contacts, compression
// positive, with the solid fraction, the coordination and the fabric of
// the contact normals.
#pragma once

#include <optional>

#include "solver/core/periodic_box.h"
#include "solver/core/simulation.h"
#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

std::optional<SceneIssue> build_periodic_cell(Scene& scene);

// The time a periodic-cell test simulates (registry.h `expected_time`):
// the compression (about ln(0.6 / phi_0) / 3 of volumetric strain at the
// servo's fastest rate, twice that to settle) and the test at its rate.
double periodic_cell_expected_time(const Scene& scene);
// The axial strain an oedometric test travels, loading and unloading, as
// estimated before it runs (its end is a stress, not a strain): for the
// progress line and the cost.
inline constexpr double kOedometricTravelEstimate = 0.04;

struct CellMeasure {
  Mat3 stress{};        // Pa, compression positive, [a][b] = -(1/V) sum f_a l_b
  Mat3 fabric{};        // <n_a n_b> over the contacts
  double volume = 0;    // m^3, the cell's
  double solid_fraction = 0;
  double coordination = 0;  // 2 contacts / particles
  double coordination_backbone = 0;  // the same without rattlers (fewer than 2 contacts)
  double kinetic = 0;   // J, of the particles' velocities relative to the flow
  int contacts = 0;
  double pressure() const { return (stress[0] + stress[4] + stress[8]) / 3; }
};
CellMeasure measure_cell(Simulation& sim);

}  // namespace simsols
