#include "solver/scene/grain_templates.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

#include "solver/scene/choices.h"
#include "solver/scene/clump.h"

namespace simsols {
namespace {

// A convex solid as half-spaces n.x <= h (n unit), optionally cut by the
// ellipsoid of semi-axes `ellipsoid` (zero: none).
struct Polyhedron {
  std::vector<std::array<double, 4>> planes;  // nx, ny, nz, h
  Vec3 ellipsoid{};
};

bool inside_polyhedron(const Polyhedron& p, const Vec3& x, double shrink) {
  for (const auto& pl : p.planes)
    if (pl[0] * x[0] + pl[1] * x[1] + pl[2] * x[2] > pl[3] - shrink) return false;
  if (p.ellipsoid[0] > 0) {
    double s = 0;
    for (int a = 0; a < 3; ++a) {
      const double e = std::max(p.ellipsoid[a] - shrink, 1e-9);
      s += (x[a] / e) * (x[a] / e);
    }
    if (s > 1) return false;
  }
  return true;
}

// A regular tetrahedron of circumradius 1: faces at distance 1/3 with
// outward normals towards minus each vertex. It is turned by a fixed,
// generic rotation: aligned with the grid, its faces would be lattice
// planes of the cell centres, and the voxel volume would jump by +-4 % from
// one resolution to the next as whole planes of centres fall in or out.
Polyhedron tetrahedron() {
  const double k = 1 / std::sqrt(3.0), h = 0.3;  // rotation 0.6 rad about (1, 2, 3)
  const double a = std::sin(h) / std::sqrt(14.0);
  const Quaternion turn{std::cos(h), a, 2 * a, 3 * a};
  const Vec3 vertex[4] = {{k, k, k}, {k, -k, -k}, {-k, k, -k}, {-k, -k, k}};
  Polyhedron p;
  for (const Vec3& v : vertex) {
    const Vec3 n = quat_rotate(turn, v);
    p.planes.push_back({-n[0], -n[1], -n[2], 1.0 / 3.0});
  }
  return p;
}

// 20 planes tangent to the ellipsoid (1, b, b) at normals drawn uniformly
// on the sphere (std::mt19937_64 from the seed; the normal's components
// are normal deviates made by Box-Muller on the engine's own doubles, so
// the draw is the same on every standard library), cut by the ellipsoid.
Polyhedron sand(double b, int seed) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
  const auto uniform = [&] { return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53; };
  const auto gaussian = [&] {
    return std::sqrt(-2 * std::log(uniform())) * std::cos(2 * 3.14159265358979323846 * uniform());
  };
  Polyhedron p;
  p.ellipsoid = {1, b, b};
  for (int i = 0; i < 20; ++i) {
    Vec3 n{gaussian(), gaussian(), gaussian()};
    n = scale(1 / norm(n), n);
    const double h = std::sqrt(n[0] * n[0] + b * b * (n[1] * n[1] + n[2] * n[2]));
    p.planes.push_back({n[0], n[1], n[2], h});
  }
  return p;
}

// A grid of `resolution` cells across [-1, 1] plus two empty cells a side.
VoxelBody empty_grid(int resolution) {
  VoxelBody b;
  b.cell = 2.0 / resolution;
  b.nx = b.ny = b.nz = resolution + 4;
  b.origin = {-1 - 2 * b.cell, -1 - 2 * b.cell, -1 - 2 * b.cell};
  b.inside.assign(static_cast<std::size_t>(b.nx) * b.ny * b.nz, 0);
  return b;
}

void fill_grid(VoxelBody& b, const std::function<bool(const Vec3&)>& inside) {
  for (int k = 0; k < b.nz; ++k)
    for (int j = 0; j < b.ny; ++j)
      for (int i = 0; i < b.nx; ++i) b.inside[b.index(i, j, k)] = inside(b.centre(i, j, k));
}

// The polyhedron with its edges and corners rounded to radius rho: its
// erosion by rho (planes and ellipsoid drawn in by rho), dilated by rho.
VoxelBody rounded(const Polyhedron& p, double rho, int resolution) {
  VoxelBody b = empty_grid(resolution);
  fill_grid(b, [&](const Vec3& x) { return inside_polyhedron(p, x, rho); });
  if (rho <= 0) return b;
  const std::vector<double> d = distance_to(b, true);
  for (std::size_t c = 0; c < d.size(); ++c) b.inside[c] = d[c] <= rho;
  return b;
}

VoxelBody superellipsoid(const Vec3& semi, double n, int resolution) {
  VoxelBody b = empty_grid(resolution);
  fill_grid(b, [&](const Vec3& x) {
    double s = 0;
    for (int a = 0; a < 3; ++a) s += std::pow(std::abs(x[a] / semi[a]), n);
    return s <= 1;
  });
  return b;
}

void check_shape(const GrainShape& s) {
  const auto out = [](const char* field, double v, const char* range) {
    throw std::invalid_argument(std::string(field) + " = " + std::to_string(v) + " is out of range, allowed " +
                                range);
  };
  if (!(s.aspect_ratio >= 1 && s.aspect_ratio <= 10)) out("aspect_ratio", s.aspect_ratio, "[1, 10]");
  if (!(s.angularity >= 0 && s.angularity <= 1)) out("angularity", s.angularity, "[0, 1]");
  if (s.resolution < 16 || s.resolution > 256) out("resolution", s.resolution, "[16, 256]");
}

}  // namespace

VoxelBody shape_body(const GrainShape& s) {
  check_shape(s);
  const double r = 1 / s.aspect_ratio, n = 2 + 8 * s.angularity, round = (1 - s.angularity) / 2;
  switch (s.form) {
    case GrainForm::Elongated: return superellipsoid({1, r, r}, n, s.resolution);
    case GrainForm::Flat: return superellipsoid({1, 1, r}, n, s.resolution);
    case GrainForm::Tetrahedral: return rounded(tetrahedron(), round / 3, s.resolution);
    case GrainForm::Sand: return rounded(sand(r, s.seed), round * 0.6 * r, s.resolution);
  }
  throw std::invalid_argument("unknown grain form");
}

Grain grain_from_solid(std::string name, const VoxelBody& solid, const FillOptions& fill, double diameter,
                       TemplateFit* fit) {
  const FillResult filled = fill_with_spheres(solid, fill);
  const MassProperties m = union_mass_properties(filled.spheres);
  const double d_eq = std::cbrt(6 * m.volume / 3.14159265358979323846);
  const double k = diameter > 0 ? diameter / d_eq : 1;
  Grain g;
  g.name = std::move(name);
  for (const ClumpSphere& s : filled.spheres)
    g.spheres.push_back({k * (s.centre[0] - m.centroid[0]), k * (s.centre[1] - m.centroid[1]),
                         k * (s.centre[2] - m.centroid[2]), k * s.radius});
  if (fit) {
    std::size_t cells = 0;
    for (std::uint8_t f : solid.inside) cells += f;
    fit->spheres = static_cast<int>(filled.spheres.size());
    fit->coverage = filled.coverage;
    fit->volume_ratio = m.volume / (cells * solid.cell * solid.cell * solid.cell);
  }
  return g;
}

std::string describe(const TemplateFit& fit) {
  char text[160];
  std::snprintf(text, sizeof text, "%d spheres cover %.1f %% of the solid; their union has %.3f of its volume",
                fit.spheres, 100 * fit.coverage, fit.volume_ratio);
  return text;
}

std::string describe(const GrainShape& s, const TemplateFit& fit) {
  char text[96];
  std::string form = choice_name(s.form);
  if (s.form != GrainForm::Tetrahedral) form += ", aspect ratio " + std::to_string(s.aspect_ratio).substr(0, 4);
  std::snprintf(text, sizeof text, "%s, angularity %.2f: ", form.c_str(), s.angularity);
  return text + describe(fit);
}

}  // namespace simsols
