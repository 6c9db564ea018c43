// A clump: a rigid grain made of overlapping spheres (docs/specimens.md).
//
// Its mass properties are those of the union of its spheres, not their sum:
// the overlaps count once. union_mass_properties() integrates the union
// exactly in x and y and by quadrature in z: each horizontal slice of the
// union is a union of disks, whose area and first and second moments
// follow in closed form from Green's theorem along the arcs of each circle
// that no other disk covers (Gauss-Legendre on each arc, exact to
// round-off for these trigonometric polynomials); the slices are then
// summed by composite Gauss-Legendre between the spheres' tops and
// bottoms. Slices of one sphere are polynomials in z, integrated exactly;
// where two circles start or stop crossing the integrand has a kink, and
// the error there falls with the number of panels (a relative 1e-9 with
// the default; tests/solver/scene/test_clump.cpp).
//
// The inertia is per unit density (m^5) about the centroid; a material's
// density multiplies it. The principal moments come with their axes, a
// right-handed frame, from Eigen's symmetric eigensolver.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "solver/common/vec3.h"

namespace simsols {

struct ClumpSphere {
  Vec3 centre{};  // m, in the clump's own frame
  double radius = 0;
};

using Matrix3 = std::array<std::array<double, 3>, 3>;

struct MassProperties {
  double volume = 0;     // m^3 of the union
  Vec3 centroid{};       // m, in the spheres' frame
  Matrix3 inertia{};     // m^5 per unit density, about the centroid, in the spheres' frame
  Vec3 principal{};      // m^5 per unit density, ascending
  std::array<Vec3, 3> axes{};  // the principal axes (unit, right-handed), in the spheres' frame
};

// `panels` Gauss-Legendre panels (8 points each) between consecutive
// sphere tops and bottoms.
MassProperties union_mass_properties(std::span<const ClumpSphere> spheres, int panels = 64);

// Area and moments of a union of disks in the plane (what a slice holds):
// area, integral of x and y, and of x^2, y^2, x y.
struct DiskUnionMoments {
  double area = 0, x = 0, y = 0, xx = 0, yy = 0, xy = 0;
};
struct Disk {
  double x = 0, y = 0, radius = 0;
};
DiskUnionMoments disk_union_moments(std::span<const Disk> disks);

}  // namespace simsols
