// Contact model: the per-material-pair coefficients of the paper's eq. (1).
//
// The force laws themselves live in kernels/contact_law.cl (the single source
// of the physics). This file derives, once per Scene, the constants those
// laws need, and the stable time step:
//
//   normal    F_n  = K_n d^{3/2} + gamma_n sqrt(m* K_n) d^{1/4} v_n,  F_n >= 0
//             K_n  = 4/3 E* sqrt(R*)            (Hertz; the paper prints d^2)
//   tangent   K_t  = 8 G* sqrt(R* d)            (Mindlin, N/m)
//             C_t  = gamma_n sqrt(m* K_t)       (the paper's C_t = C_n sqrt(K_t/K_n)
//                                                with K_n the Hertz secant stiffness)
//             |F_t| <= mu_s F_n
//   rolling   M    = -min(mu_r F_n, I* |w_r| / dt) w_r/|w_r|
//
// gamma_n is not the linear-spring formula: for a Hertz spring with a
// d^{1/4} dashpot the restitution coefficient depends on gamma_n alone
// (not on the impact speed), and damping_for_restitution() inverts that
// relation numerically; the kernels evaluate the dashpot at the time level
// of the positions (contact_law.cl), so the simulated restitution equals
// the input. See docs/model.md.
#pragma once

#include <vector>

#include "solver/scene/scene.h"

namespace simsols {

// Coefficients of one (material a, material b) pair, SI units.
struct PairCoefficients {
  double e_star = 0;      // effective Young modulus E*, Pa
  double g_star = 0;      // effective shear modulus G*, Pa
  double gamma_n = 0;     // dimensionless damping, from the pair restitution
  double restitution = 1;
  double sliding_friction = 0;
  double rolling_friction = 0;  // m
  // capillary cohesion (zero without it): gamma cos(theta), N/m; liquid
  // volume per bridge, m^3; rupture distance (Lian et al. 1993), m
  double capillary_tension = 0;
  double liquid_volume = 0;
  double rupture_distance = 0;
};

// Pair table, row-major [a * n + b], symmetric.
struct PairTable {
  int n = 0;
  std::vector<PairCoefficients> pairs;
  const PairCoefficients& at(int a, int b) const { return pairs[a * n + b]; }
};

PairTable make_pair_table(const Scene& scene);

// Dimensionless damping gamma such that a Hertz contact with
// F = K d^{3/2} + gamma sqrt(m K) d^{1/4} v (clamped at F >= 0) rebounds with
// restitution `e` in (0, 1]. gamma(1) = 0. Accurate to ~1e-10 in e. Throws
// std::invalid_argument for e <= 0 (or not a number): no finite gamma stops
// the rebound, e falls as ~1.24 / gamma^2 (docs/model.md).
double damping_for_restitution(double e);

// The smallest restitution a scene may ask for (scene validation): below it
// a contact at 10 m/s is over in too few steps of the default time step for
// the simulated e to stay within 1 % of the input (docs/model.md).
inline constexpr double kMinRestitution = 0.01;
// The inverse: restitution produced by a dimensionless damping gamma >= 0.
double restitution_for_damping(double gamma);

// Rayleigh time step of the smallest particle over all materials used:
//   dt_R = pi R sqrt(rho / G) / (0.1631 nu + 0.8766).
// Returns 0 when the scene has no particles.
double rayleigh_time_step(const Scene& scene);

// The time step a run uses: numerics.dt if set, else dt_fraction x dt_R.
double effective_time_step(const Scene& scene);

}  // namespace simsols
