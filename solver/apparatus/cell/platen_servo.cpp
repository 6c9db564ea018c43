#include "solver/apparatus/cell/platen_servo.h"

#include "solver/scene/clump.h"

#include <algorithm>
#include <cmath>

#include "solver/scene/contact_model.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kGainFraction = 0.5;
constexpr double kIntegralPeriods = 5.0;

}  // namespace

SpecimenStats specimen_stats(const Scene& scene, int wall_material) {
  SpecimenStats s;
  double d = 0, mass = 0;
  const std::vector<double> solid = solid_volumes(scene);  // clumps' overlaps once
  const size_t beads = scene.specimen_count();  // a membrane's beads are no part of it
  for (size_t i = 0; i < beads; ++i) {
    const Particle& p = scene.particles[i];
    d += 2 * p.radius;
    mass += p.clump < 0 ? scene.materials[p.material].density * 4.0 / 3.0 * kPi * std::pow(p.radius, 3)
                        : scene.materials[p.material].density * solid[i];
    s.volume += solid[i];
  }
  const double n = static_cast<double>(beads);
  s.count = n;
  s.diameter = d / n;
  s.bead_mass = mass / n;
  s.density = scene.materials[scene.particles[0].material].density;
  const PairTable pairs = make_pair_table(scene);
  const double e_star = pairs.at(scene.particles[0].material, wall_material).e_star;
  s.k_hertz = 4.0 / 3.0 * e_star * std::sqrt(s.diameter / 2);
  s.mass = mass;
  double top = 0;
  for (size_t i = 0; i < beads; ++i)
    top = std::max(top, scene.particles[i].position[2] + scene.particles[i].radius);
  s.layers = std::max(1.0, top / s.diameter);
  return s;
}

PlatenServo tune_platen_servo(const SpecimenStats& s, double area, double stress, double dt,
                              double given_gain, double given_integral_time) {
  const double d = s.diameter;
  const double contacts = area / (d * d);
  const double f_contact = stress * d * d;
  const double k_contact = 1.5 * std::cbrt(f_contact) * std::pow(s.k_hertz, 2.0 / 3.0);
  const double k_platen = contacts * k_contact;
  PlatenServo p;
  p.gain = given_gain > 0 ? given_gain : kGainFraction / (k_platen * dt);
  const double period = 2 * kPi * std::sqrt(s.mass / (k_platen / s.layers));
  p.integral_time = given_integral_time > 0 ? given_integral_time : kIntegralPeriods * period;
  return p;
}

}  // namespace simsols
