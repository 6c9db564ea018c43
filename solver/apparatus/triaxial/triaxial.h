// Triaxial cell: a cuboid specimen between six rigid plates.
//
// build_triaxial() places the specimen (specimen.h) in the cell's initial
// footprint and appends six rectangle walls: the fixed floor, four sides
// (x0, x1, y0, y1) and the top platen, the last five servo-controlled by
// the loading programme (triaxial_programme.h). Each plate reaches past the
// cell's edges by half the cell's largest side, so the plates can move in
// and out (a true-triaxial apparatus' plates slide past each other) and
// still close every edge: walls do not touch each other, only beads.
#pragma once

#include <optional>

#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

// Appends the apparatus (and the specimen) to `scene`; returns the first
// problem, with its field under "triaxial". With cell = "membrane" it
// also appends the membrane's beads after the specimen's (scene.h,
// Membrane), held above the cell.
std::optional<SceneIssue> build_triaxial(Scene& scene);

// The porosity the membrane's rows are planned for at scene build: they
// cover the height the specimen will have at this porosity.
inline constexpr double kMembranePlannedPorosity = 0.4;

// The inertial number of an axial strain rate and back:
// I = rate d sqrt(rho / p).
double triaxial_inertial_number(double strain_rate, double d, double density, double p);
double triaxial_strain_rate(double inertial_number, double d, double density, double p);

// The time a triaxial test simulates (registry.h `expected_time`): a third
// of the settling and consolidation allowances (they end at equilibrium,
// usually sooner) and the compression at its strain rate.
double triaxial_expected_time(const Scene& scene);

}  // namespace simsols
