// Shear box: the direct shear apparatus as walls, and its specimen.
//
// build_shear_box() is to a [shear_box] what a generator is to particles: it
// expands the scene's ShearBox (Scene::apparatus, scene.h) into twelve rectangle
// walls appended to Scene::walls (floor, the lower half's four side plates
// and frame, the upper half's four and frame, the platen) and, unless the
// specimen is given, places the beads. The frames stand for the thickness of
// a real box's walls: without them, shearing by dx opens a slot dx wide
// under the upper half's x0 wall and over the lower half's x1 wall, and
// beads smaller than dx pour out through it.
// The specimen is placed as specimen.h describes (layers, pour, given).
// The halves are rectangles, not planes, so a bead in the gap meets their
// edges: with gap < the smallest radius no bead centre can pass a wall.
// The default split height is mid-height of the specimen: for Layers between
// the two layers nearest mid-height, at the height they reach once each layer
// has nested into the one below as far as its clearance lets it shift (an
// estimate made before settling: d/sqrt(2) apart when the clearance allows
// half a diameter, d apart for Spread); for Given beads half their height;
// for a pour half the height its solid volume (a clump's overlaps once)
// fills at the tamping target's void ratio, else at a solid fraction 0.6.
// Automatic values (gap, split height, wall material) are resolved into the
// ShearBox, so to_toml() writes a scene that rebuilds the same walls.
#pragma once

#include <optional>

#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/specimen/specimen.h"
#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

// Appends the apparatus (and the specimen) to `scene`; returns the first
// problem, with its field under "shear_box".
std::optional<SceneIssue> build_shear_box(Scene& scene);

// A prepared specimen (tamped, grown) whose highest grain's top is at `top`
// (m, from the floor): a problem when the shear plane is not below it.
std::optional<SceneIssue> check_shear_box_specimen_top(const Scene& scene, double top);

// A size study's box (registry.h `resize`): resize_cell (cell_walls.h),
// the shear displacement times `across` (the halves travel the same share
// of the box) and an explicit split height times `height`.
void resize_shear_box(Scene& scene, double across, double height);

// The time a shear test simulates (registry.h `expected_time`): its
// settling allowance, 0.05 s of consolidation and the travel at its speed.
double shear_box_expected_time(const Scene& scene);

// The run profiles' levers (registry.h): the normal stress, and the target
// inertial number of an automatic shear speed (a given shear_speed is kept).
double shear_box_profile_stress(const Scene& scene);
void set_shear_box_inertial_number(Scene& scene, double inertial_number);

// Inside area of the box (m^2) and its corrected value after a relative
// displacement dx of the halves.
double shear_area(const ShearBox& box);
double shear_area_corrected(const ShearBox& box, double dx);

// The square layer the box allows for diameter d (specimen.h).
LayerGrid layer_grid(const ShearBox& box, double d);
int beads_per_layer(const ShearBox& box, double d);

// The inertial number of a shear at speed v across a specimen of height H,
// beads of diameter d and density rho under sigma: I = (v/H) d sqrt(rho/sigma),
// and the speed that gives a target I: v = I (H/d) sqrt(sigma/rho).
double inertial_number_of(double speed, double height, double d, double density, double sigma);
double speed_for_inertial_number(double inertial_number, double height, double d, double density,
                                 double sigma);

}  // namespace simsols
