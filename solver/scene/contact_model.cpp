#include "solver/scene/contact_model.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace simsols {
namespace {

// Dimensionless Hertz contact with a d^{1/4} dashpot, in units where the
// impact speed is 1 and K/m = 1 (see docs/model.md):
//   x'' = -max(0, x^{3/2} + gamma x^{1/4} x'),  x(0) = 0, x'(0) = 1.
// The contact ends when x returns to 0; the restitution is -x'(end).
struct Xv {
  double x, v;
};

Xv rhs(const Xv& s, double gamma) {
  const double x = std::max(s.x, 0.0);
  const double sx = std::sqrt(x);
  const double f = x * sx + gamma * std::sqrt(sx) * s.v;
  return {s.v, -std::max(f, 0.0)};
}

double simulate_restitution(double gamma) {
  const double h = 1e-4;  // contact lasts ~3 time units
  Xv s{0.0, 1.0};
  for (int i = 0; i < 10000000; ++i) {
    const Xv k1 = rhs(s, gamma);
    const Xv k2 = rhs({s.x + 0.5 * h * k1.x, s.v + 0.5 * h * k1.v}, gamma);
    const Xv k3 = rhs({s.x + 0.5 * h * k2.x, s.v + 0.5 * h * k2.v}, gamma);
    const Xv k4 = rhs({s.x + h * k3.x, s.v + h * k3.v}, gamma);
    const Xv n{s.x + h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x),
               s.v + h / 6 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v)};
    if (i > 0 && n.x <= 0.0) return -n.v;
    s = n;
    // Once the force has vanished on the way out, the motion is free flight
    // at constant speed until separation: the restitution is known already.
    if (s.v < 0 && rhs(s, gamma).v >= 0) return -s.v;
  }
  return -s.v;
}

}  // namespace

double restitution_for_damping(double gamma) { return simulate_restitution(gamma); }

double damping_for_restitution(double e) {
  if (!(e > 0.0))
    throw std::invalid_argument("restitution " + std::to_string(e) +
                                ": no finite damping gives a restitution of 0 or less");
  if (e >= 1.0) return 0.0;
  static std::mutex mutex;
  static std::map<double, double> cache;
  std::lock_guard lock(mutex);
  if (auto it = cache.find(e); it != cache.end()) return it->second;
  // e(gamma) decreases monotonically from 1; bracket then bisect.
  double lo = 0.0, hi = 1.0;
  while (simulate_restitution(hi) > e) hi *= 2.0;
  for (int it = 0; it < 60 && hi - lo > 1e-10 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (simulate_restitution(mid) > e ? lo : hi) = mid;
  }
  const double gamma = 0.5 * (lo + hi);
  cache.emplace(e, gamma);
  return gamma;
}

PairTable make_pair_table(const Scene& scene) {
  PairTable t;
  t.n = static_cast<int>(scene.materials.size());
  t.pairs.resize(static_cast<size_t>(t.n) * t.n);
  for (int a = 0; a < t.n; ++a) {
    for (int b = 0; b < t.n; ++b) {
      const Material& ma = scene.materials[a];
      const Material& mb = scene.materials[b];
      PairCoefficients p;
      p.e_star = 1.0 / ((1 - ma.poisson_ratio * ma.poisson_ratio) / ma.young_modulus +
                        (1 - mb.poisson_ratio * mb.poisson_ratio) / mb.young_modulus);
      const double ga = ma.young_modulus / (2 * (1 + ma.poisson_ratio));
      const double gb = mb.young_modulus / (2 * (1 + mb.poisson_ratio));
      p.g_star = 1.0 / ((2 - ma.poisson_ratio) / ga + (2 - mb.poisson_ratio) / gb);
      p.restitution = 0.5 * (ma.restitution + mb.restitution);
      p.sliding_friction = std::min(ma.sliding_friction, mb.sliding_friction);
      p.rolling_friction = std::min(ma.rolling_friction, mb.rolling_friction);
      for (const PairOverride& o : scene.pair_overrides) {
        if ((o.material_a == a && o.material_b == b) || (o.material_a == b && o.material_b == a)) {
          if (o.restitution) p.restitution = *o.restitution;
          if (o.sliding_friction) p.sliding_friction = *o.sliding_friction;
          if (o.rolling_friction) p.rolling_friction = *o.rolling_friction;
        }
      }
      if (scene.effects.cohesion == CohesionModel::Capillary) {
        const Capillary& c = scene.effects.capillary;
        double volume = c.liquid_volume, angle = c.contact_angle;
        for (const PairOverride& o : scene.pair_overrides)
          if ((o.material_a == a && o.material_b == b) || (o.material_a == b && o.material_b == a)) {
            volume = o.liquid_volume.value_or(volume);
            angle = o.contact_angle.value_or(angle);
          }
        p.capillary_tension = c.surface_tension * std::cos(angle);
        p.liquid_volume = volume;
        p.rupture_distance = capillary_rupture_distance(volume, angle);
      }
      p.gamma_n = damping_for_restitution(p.restitution);
      t.pairs[a * t.n + b] = p;
    }
  }
  return t;
}

double rayleigh_time_step(const Scene& scene) {
  double dt = 0;
  for (const Particle& p : scene.particles) {
    const Material& m = scene.materials.at(p.material);
    const double g = m.young_modulus / (2 * (1 + m.poisson_ratio));
    const double t = std::numbers::pi * p.radius * std::sqrt(m.density / g) /
                     (0.1631 * m.poisson_ratio + 0.8766);
    if (dt == 0 || t < dt) dt = t;
  }
  return dt;
}

double effective_time_step(const Scene& scene) {
  if (scene.numerics.dt > 0) return scene.numerics.dt;
  return scene.numerics.dt_fraction * rayleigh_time_step(scene);
}

}  // namespace simsols
