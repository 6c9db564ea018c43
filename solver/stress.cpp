#include "stress.h"

#include <algorithm>
#include <cmath>

namespace simsols {
namespace {

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Closest point of wall `w` (reference point moved to `p`) to x.
Vec3 closest_point(const Wall& w, const Vec3& p, const Vec3& x) {
  const Vec3 d{x[0] - p[0], x[1] - p[1], x[2] - p[2]};
  if (w.shape == WallShape::Plane) {
    const double s = dot(d, w.normal);
    return {x[0] - s * w.normal[0], x[1] - s * w.normal[1], x[2] - s * w.normal[2]};
  }
  const Vec3& u = w.axis_u;
  const Vec3 v{w.normal[1] * u[2] - w.normal[2] * u[1], w.normal[2] * u[0] - w.normal[0] * u[2],
               w.normal[0] * u[1] - w.normal[1] * u[0]};
  const double a = std::clamp(dot(d, u), -w.half_u, w.half_u);
  const double b = std::clamp(dot(d, v), -w.half_v, w.half_v);
  return {p[0] + a * u[0] + b * v[0], p[1] + a * u[1] + b * v[1], p[2] + a * u[2] + b * v[2]};
}

// Fraction of the segment from z0 to z0 + lz inside [lo, hi].
double inside_fraction(double z0, double lz, double lo, double hi) {
  if (lz == 0) return z0 >= lo && z0 <= hi ? 1 : 0;
  const double a = std::min(z0, z0 + lz), b = std::max(z0, z0 + lz);
  const double overlap = std::max(0.0, std::min(b, hi) - std::max(a, lo));
  return overlap / (b - a);
}

}  // namespace

Tensor3 love_weber_slab(Simulation& sim, double z_lo, double z_hi, double area) {
  const ParticleSnapshot snap = sim.snapshot();
  const std::vector<ContactForce> contacts = sim.contacts();
  const std::vector<Vec3> points = wall_points(sim.model(), sim.state());
  const std::vector<Wall>& walls = sim.scene().walls;
  Tensor3 s{};
  for (const ContactForce& c : contacts) {
    const Vec3& xa = snap.position[c.a];
    const Vec3 xb = c.b >= 0 ? snap.position[c.b]
                             : closest_point(walls[-1 - c.b], points[-1 - c.b], xa);
    const Vec3 l{xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]};
    const double w = inside_fraction(xa[2], l[2], z_lo, z_hi);
    if (w == 0) continue;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s[i][j] -= w * c.force[i] * l[j];
  }
  const double volume = area * (z_hi - z_lo);
  for (auto& row : s)
    for (double& v : row) v /= volume;
  return s;
}

}  // namespace simsols
