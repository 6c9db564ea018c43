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
#include "solver/scene/scene.h"

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
// sphere tops and bottoms, fewer (down to 2) once there are more than 8
// such cuts, so the total stays near 8 x panels: a 32-sphere grain costs
// about 0.3 s, with its volume exact to ~1e-11.
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

// Unit quaternions (w, x, y, z): products and rotations.
using Quaternion = std::array<double, 4>;
Quaternion quat_multiply(const Quaternion& a, const Quaternion& b);
Vec3 quat_rotate(const Quaternion& q, const Vec3& v);

// A grain as a rigid body: its unit-density mass properties, and its
// spheres about the centroid in the principal frame (the body frame the
// kernels integrate in); `to_grain` turns the principal frame into the
// grain's own.
struct GrainBody {
  MassProperties mass;
  std::vector<Vec3> offsets;  // m, principal frame
  std::vector<double> radii;
  Quaternion to_grain{1, 0, 0, 0};
};
GrainBody grain_body(const Grain& grain);
// The diameter of the sphere of the body's volume, (6 V / pi)^(1/3): a
// grain's size as a grading counts it.
double volume_equivalent_diameter(const GrainBody& body);
// The same body `scale` times larger (lengths x s, volume x s^3, inertia x s^5).
GrainBody scaled(const GrainBody& body, double scale);

// Appends clump c's member spheres to scene.particles (body scaled by
// c.scale, placed from its position and orientation, moving with its
// velocities) and c, with its member range, to scene.clumps.
void add_clump(Scene& scene, Clump c, const GrainBody& body);

// Each particle's share of the solid volume (m^3): a free sphere's own
// volume; a clump member's share of its clump's union volume, in
// proportion to its sphere's volume (the shares of a clump add up to the
// union's volume, its overlaps counted once).
std::vector<double> solid_volumes(const Scene& scene);

// A unit quaternion drawn uniformly over rotations from three numbers
// uniform in [0, 1) (Shoemake 1992).
Quaternion uniform_rotation(double u1, double u2, double u3);

// The clump's orientation in the body (principal) frame: body to scene.
Quaternion body_orientation(const Clump& c, const GrainBody& body);

}  // namespace simsols
