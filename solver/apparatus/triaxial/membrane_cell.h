// The triaxial cell's membrane (cell = "membrane"): where its beads go when
// it takes the consolidated specimen over from the side plates, and what is
// read from them while it holds it.
//
// The membrane (scene.h, Membrane; kernels/membrane.cl) is a lattice of
// rows x cols beads of radius r_m. Wrapped about the cuboid the plates
// leave, its rings follow the rectangle grown by r_m (sides and quarter
// circles about the corners: the beads touch the specimen where the plates
// did), its rows run from r_m above the floor to r_m below the platen: the
// end rows are sealed to the plates in height only and carry the pressure
// like the others (end rows held still across held the specimen's ends in
// a rigid collar, and the sides of a specimen of 5.5 diameters carried 40 %
// more than the cell pressure by 3 % of axial strain), and
// its bonds are at rest: the hoop rest length is the ring's mean chord, the
// axial one the row pitch, each direction's spring E t times the other
// spacing over its own (a sheet of E t, membrane.cl).
//
// Measured from the beads' positions:
//   the volume inside: per ring the area inside its beads' inner face,
//     the polygon of centres shrunk by r_m (A - P r_m + pi r_m^2, exact for
//     a convex ring; the beads overlap their neighbours, so the face is
//     nearly smooth), linear in z between the rings' mean heights (the end
//     rings' own area out to the floor and the platen), integrated from
//     the floor to the platen;
//   the mean cross-section: that volume over the height;
//   the hoop share of the radial stress: a ring of perimeter P under a
//     hoop tension T (N/m: the mean bond force over the local row pitch)
//     presses on what it wraps with 2 pi T / P on average (the mean
//     curvature of a closed curve is 2 pi / P), averaged over the free
//     rings. It adds to the cell pressure, as the membrane correction of
//     laboratory practice says.
#pragma once

#include <vector>

#include "solver/common/vec3.h"
#include "solver/core/simulation.h"
#include "solver/core/stress.h"

namespace simsols {

// n points (z = 0) evenly along the rectangle [x0, x1] x [y0, y1] grown by
// `offset`: its four sides and quarter circles about its corners,
// counter-clockwise seen from above, starting at the middle of the x1 side.
std::vector<Vec3> membrane_ring(double x0, double x1, double y0, double y1, double offset, int n);

struct CuboidExtent {
  double x0, x1, y0, y1, z0, z1;
};

struct MembraneWrap {
  std::vector<Vec3> positions;              // the beads, row by row
  Simulation::MembraneSetting setting;      // free, at `pressure`, bonds at rest
};
MembraneWrap wrap_cuboid(const Membrane& m, double bead_radius, double pressure, const CuboidExtent& box);

struct MembraneShape {
  double volume = 0;       // m^3, inside the membrane
  double area = 0;         // m^2, volume / height
  double hoop_stress = 0;  // Pa, the hoop tension's share of the radial stress
};
// `position`: every particle's (a snapshot); z0, z1: the floor and the platen.
MembraneShape measure_membrane(const std::vector<Vec3>& position, const Membrane& m, double bead_radius,
                               double z0, double z1, const Simulation::MembraneSetting& setting);

// The membrane's share of the platen's axial stress (Pa): the axial load
// it carries through the grains it grips, (1/V) sum f_z (z_c - z0) over the
// contacts between a membrane bead and a bead of [0, inside) (f on the
// inside bead, z_c the contact point, z0 the floor). The platen's force
// over the mean cross-section is the specimen's own axial stress plus this
// share (the Love-Weber stress from the boundary forces), so the specimen's
// is the platen's minus it: the membrane correction of laboratory
// practice, measured here rather than estimated. Positive where the
// membrane carries compression.
double membrane_axial_share(const ContactSample& sample, size_t inside, double volume, double z0);

// The same share as laboratory practice estimates it, a cylindrical shell
// of sheet stiffness E t (N/m) shortened with the specimen by the axial
// strain: it carries E t strain pi D over the area pi D^2 / 4, D the
// diameter of the mean cross-section `area` (m^2). Pa.
double membrane_shell_share(double stiffness, double axial_strain, double area);

// Contacts per bead of the beads [0, inside): bead pairs count for both,
// contacts with the membrane or a wall for the bead.
double inside_coordination(const ContactSample& sample, size_t inside);

}  // namespace simsols
