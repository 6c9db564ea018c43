#include "solver/core/stress.h"

#include <algorithm>
#include <cmath>

namespace simsols {
namespace {


// Fraction of the segment from z0 to z0 + lz inside [lo, hi].
double inside_fraction(double z0, double lz, double lo, double hi) {
  if (lz == 0) return z0 >= lo && z0 <= hi ? 1 : 0;
  const double a = std::min(z0, z0 + lz), b = std::max(z0, z0 + lz);
  const double overlap = std::max(0.0, std::min(b, hi) - std::max(a, lo));
  return overlap / (b - a);
}

}  // namespace

ContactSample sample_contacts(Simulation& sim) {
  ContactSample s;
  s.beads = sim.snapshot();
  s.contacts = sim.contacts();
  s.wall_points = wall_points(sim.model(), sim.state());
  s.walls = sim.scene().walls;
  for (size_t w = 0; w < s.walls.size(); ++w)
    if (s.walls[w].tilts) s.walls[w] = tilted_wall(s.walls[w], sim.wall_tilt(int(w)).angle);
  s.body_centre = s.beads.position;
  const std::vector<Particle>& particles = sim.scene().particles;
  if (!sim.scene().clumps.empty()) {
    const std::vector<ClumpState> clumps = sim.clumps();
    for (size_t i = 0; i < particles.size(); ++i)
      if (particles[i].clump >= 0) s.body_centre[i] = clumps[particles[i].clump].position;
  }
  return s;
}

Tensor3 love_weber_slab(Simulation& sim, double z_lo, double z_hi, double area) {
  return love_weber_slab(sample_contacts(sim), sim.scene().walls, z_lo, z_hi, area);
}

Tensor3 love_weber_slab(const ContactSample& sample, const std::vector<Wall>& walls, double z_lo,
                        double z_hi, double area) {
  const ParticleSnapshot& snap = sample.beads;
  const std::vector<ContactForce>& contacts = sample.contacts;
  const std::vector<Vec3>& points = sample.wall_points;
  Tensor3 s{};
  const std::vector<Vec3>& centre = sample.body_centre.empty() ? snap.position : sample.body_centre;
  for (const ContactForce& c : contacts) {
    const Vec3& xa = centre[c.a];
    const Vec3 xb = c.b >= 0 ? centre[c.b]
                             : wall_closest_point(walls[-1 - c.b], points[-1 - c.b], snap.position[c.a]);
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

std::optional<BoundaryContact> boundary_contact(const ContactSample& sample, const ContactForce& c,
                                                size_t inside) {
  if (c.b < 0) return std::nullopt;
  const bool a_in = size_t(c.a) < inside, b_in = size_t(c.b) < inside;
  if (a_in == b_in) return std::nullopt;
  const ParticleSnapshot& snap = sample.beads;
  const size_t in = a_in ? size_t(c.a) : size_t(c.b), out = a_in ? size_t(c.b) : size_t(c.a);
  const double share = snap.radius[in] / (snap.radius[in] + snap.radius[out]);
  const Vec3& xi = snap.position[in];
  const Vec3& xo = snap.position[out];
  BoundaryContact k;
  k.bead = in;
  k.force = a_in ? c.force : Vec3{-c.force[0], -c.force[1], -c.force[2]};
  k.point = {xi[0] + share * (xo[0] - xi[0]), xi[1] + share * (xo[1] - xi[1]),
             xi[2] + share * (xo[2] - xi[2])};
  return k;
}

Tensor3 love_weber_inside(const ContactSample& sample, size_t inside, double volume) {
  const ParticleSnapshot& snap = sample.beads;
  const std::vector<Vec3>& centre = sample.body_centre.empty() ? snap.position : sample.body_centre;
  Tensor3 s{};
  const auto add = [&](const Vec3& f, const Vec3& from, const Vec3& to) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s[i][j] -= f[i] * (to[j] - from[j]);
  };
  for (const ContactForce& c : sample.contacts) {
    const size_t a = size_t(c.a);
    const bool a_in = a < inside, b_in = c.b >= 0 && size_t(c.b) < inside;
    if (c.b < 0) {
      if (a_in)
        add(c.force, centre[a],
            wall_closest_point(sample.walls[-1 - c.b], sample.wall_points[-1 - c.b], snap.position[a]));
      continue;
    }
    if (a_in && b_in) {
      add(c.force, centre[a], centre[size_t(c.b)]);
    } else if (const auto k = boundary_contact(sample, c, inside)) {
      add(k->force, centre[k->bead], k->point);  // a boundary force at its contact point
    }
  }
  for (auto& row : s)
    for (double& v : row) v /= volume;
  return s;
}

ContactSample beads_inside(const ContactSample& sample, size_t inside) {
  ContactSample out = sample;
  std::erase_if(out.contacts, [&](const ContactForce& c) {
    return size_t(c.a) >= inside || (c.b >= 0 && size_t(c.b) >= inside);
  });
  return out;
}

}  // namespace simsols
