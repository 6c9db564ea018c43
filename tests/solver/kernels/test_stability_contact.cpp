// Stability suite, contact cases (ctest label `stability`): rolling friction
// at rest and near rest (case 2) and the tangential history of a rigidly
// rotating pair (case 3a), re-formed contacts (3b) and fast impacts (5). Each case asserts a bound that could fail and prints its
// measured margins as [measure] lines. The CI form is reduced; with
// SIMSOLS_STABILITY_FULL=1 the same tests run larger counts and longer
// windows (each prints which form ran).
#include <CL/cl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "solver/core/cl_program.h"
#include "solver/scene/contact_model.h"
#include "solver/core/real_packer.h"
#include "solver/kernels/kernel_source.h"
#include "solver/io/scene_toml.h"
#include "tests/support/law_driver.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

bool full_form() { return stability_full_form(); }
const char* form() { return full_form() ? "full form" : "reduced form"; }

double real_eps(Precision p) { return p == Precision::Float ? 0x1p-23 : 0x1p-52; }


// Glass beads of the paper: 2.38125 mm diameter.
constexpr double kR = 2.38125e-3 / 2;
constexpr double kG = 9.81;

// Hertz overlap of a sphere resting on a plane under its own weight.
double resting_overlap(const Scene& s, const Particle& p) {
  const double k = 4.0 / 3.0 * e_star(s.materials[p.material]) * std::sqrt(p.radius);
  return std::pow(mass(s, p) * kG / k, 2.0 / 3.0);
}

// Energy bookkeeping: E_k may not exceed the lowest energy seen before it by
// more than `tol`. Returns the largest rise found (negative: none).
struct Monotone {
  double lowest = INFINITY, worst_rise = -INFINITY;
  void add(double e) {
    if (std::isfinite(lowest)) worst_rise = std::max(worst_rise, e - lowest);
    lowest = std::min(lowest, e);
  }
};

// ===========================================================================
// Case 2. Rolling friction at rest and near rest.
//
// The rolling torque is a constant mu_r F_n, limited so that it never
// reverses the relative rolling velocity within a step (contact_law.cl).
// A constant torque applied naively flips w every step once the bead is
// nearly stopped (chatter: w changing sign with growing amplitude), makes a
// bead at rest walk (creep), and feeds energy in. Here, with the paper's
// glass mu_r = 5e-5 m and mu_s = 0.02:
//   near rest  a glass sphere on a floor given a small roll: w_y, sampled
//              every few steps, never changes sign with a growing amplitude
//              (each half-cycle's peak no larger than the previous one's),
//              the sphere stops within 5 % of the constant-torque time
//              t = 7 R v0 / (5 mu_r g), and then holds: its centre moves
//              less than 1e-9 R over the hold window.
//   energy     kinetic + gravitational + elastic (Observables) never rises
//              above its lowest earlier value by more than the round-off of
//              the sum (a few ulps of its largest term).
//   pile       a few dozen beads poured into a small box and settled: over a
//              long window after settling, no bead moves more than a bound
//              tied to the contact scale (see PileSettles).
// ===========================================================================

Scene sphere_on_floor(Precision precision, const Material& m, double R, double v0) {
  Scene s = empty_scene(precision, m);
  s.effects.gravity = {0, 0, -kG};
  Particle p = sphere(R, {0, 0, R}, {v0, 0, 0}, {0, v0 / R, 0});
  p.position[2] = R - resting_overlap(s, p);
  s.particles = {p};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  return s;
}

// Elastic energy of the tangential springs, 1/2 k_t |xi|^2 with
// k_t = 8 G* sqrt(R* d) (contact_law.cl): Observables counts only the normal
// part, and a loaded spring that relaxes would otherwise look like energy
// appearing. Bead pairs and plane walls (the scenes here use no rectangles).
double spring_energy(Simulation& sim, const ParticleSnapshot& q) {
  const Model& m = sim.model();
  State& s = sim.state();
  if (!m.config().friction) return 0;
  const int n = s.n;
  const double dt = m.dt();
  std::vector<Vec3> x(n);  // x_n, where the springs were evaluated
  for (int i = 0; i < n; ++i) x[i] = sub(q.position[i], scale(dt, q.velocity[i]));
  const Scene& sc = m.scene();
  double e = 0;
  const UpperLists l = read_upper_lists(m, s);
  const std::vector<double> sp = read_reals(m, s.spring, size_t(s.up_slots) * 4);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < l.upper[i]; ++k) {
      const size_t slot = l.slot(i, k);
      const int j = l.nbr[slot];
      const Vec3 xi{sp[l.real_at(slot, 0)], sp[l.real_at(slot, 1)], sp[l.real_at(slot, 2)]};
      const double d = q.radius[i] + q.radius[j] - norm(sub(x[j], x[i]));
      if (d <= 0) continue;
      const double rs = q.radius[i] * q.radius[j] / (q.radius[i] + q.radius[j]);
      const double g = m.pairs().at(q.material[i], q.material[j]).g_star;
      e += 0.5 * 8 * g * std::sqrt(rs * d) * dot(xi, xi);
    }
  if (m.config().walls) {
    const WallSlots wl = read_wall_slots(m, s);
    const std::vector<double> ws = read_reals(m, s.wall_spring, size_t(s.wall_slots) * 4);
    for (int w = 0; w < m.walls(); ++w) {
      const Wall& wall = sc.walls[w];
      for (int i = 0; i < n; ++i) {
        if (!wl.near(i, w)) continue;
        const size_t slot = wl.slot(i, w);
        const Vec3 xi{ws[4 * slot], ws[4 * slot + 1], ws[4 * slot + 2]};
        const double d = q.radius[i] - dot(sub(x[i], wall.point), wall.normal);
        if (d <= 0 || dot(xi, xi) == 0) continue;
        const double g = m.pairs().at(q.material[i], wall.material).g_star;
        e += 0.5 * 8 * g * std::sqrt(q.radius[i] * d) * dot(xi, xi);
      }
    }
  }
  return e;
}

// Total mechanical energy: Observables (kinetic, gravitational, normal
// elastic) plus the tangential springs. `scale` gets the sum of magnitudes,
// the size of the round-off of the total.
double mechanical_energy(Simulation& sim, double* scale = nullptr) {
  const Observables o = sim.observe();
  const double t = spring_energy(sim, sim.snapshot());
  if (scale)
    *scale = std::max(*scale, std::fabs(o.gravitational_energy) + o.elastic_energy + o.kinetic() + t);
  return o.total_energy() + t;
}

struct RollOutcome {
  double t_stop = -1;        // first time v_x <= 1e-3 v0
  double growth = 0;         // largest ratio of a half-cycle's w_y peak to the previous one
  int sign_changes = 0;      // of w_y
  double first_peak = 0;     // largest |w_y| after the first sign change
  double spin_while_sliding = 0;  // largest |w_y| once w_y has first dropped below 1e-3 v0/R
  double creep = 0;          // centre displacement over the hold window, m
  double final_w = 0;
  double energy_rise = 0, energy_tol = 0;
};

// Rolls a sphere off at v0 (w = v0/R), watches it stop, then holds it: the
// hold window starts kSettle steps after the stop, once the rocking on the
// tangential spring that follows the stop has decayed (it is gone, to the
// last bit of the position, after ~12 000 steps).
constexpr std::int64_t kSettle = 20000;
RollOutcome roll_and_hold(Precision prec, double mu_s, double v0, double t_expect,
                          std::int64_t hold) {
  const double mu_r = 5e-5;
  Simulation sim(default_device(), sphere_on_floor(prec, glass(0.87, mu_s, mu_r), kR, v0));
  RollOutcome out;
  std::vector<double> peaks{0};
  double last_w = 0, scale = 0;
  bool spin_stopped = false;
  Vec3 stop_pos{};
  std::int64_t stop_step = -1;
  Monotone energy;  // from step 1: before it no force has been evaluated
  const std::int64_t limit = static_cast<std::int64_t>(1.5 * t_expect / sim.dt());
  while (true) {
    // every 10 steps while it moves, every 100 while it is held
    const bool moving = stop_step < 0 || sim.steps() < stop_step + kSettle;
    sim.advance(moving ? 10 : 100);
    const ParticleSnapshot q = sim.snapshot();
    energy.add(mechanical_energy(sim, &scale));
    const double w = q.angular_velocity[0][1];
    if (w != 0 && last_w != 0 && (w > 0) != (last_w > 0)) {
      ++out.sign_changes;
      peaks.push_back(0);
    }
    if (w != 0) last_w = w;
    peaks.back() = std::max(peaks.back(), std::fabs(w));
    if (std::fabs(w) < 1e-3 * v0 / kR) spin_stopped = true;
    if (spin_stopped && stop_step < 0) out.spin_while_sliding = std::max(out.spin_while_sliding, std::fabs(w));
    if (stop_step < 0 && q.velocity[0][0] <= 1e-3 * v0) {
      out.t_stop = sim.time();
      stop_step = sim.steps();
    }
    if (stop_step >= 0 && sim.steps() == stop_step + kSettle) stop_pos = q.position[0];
    if (stop_step >= 0 && sim.steps() >= stop_step + kSettle + hold) {
      out.creep = norm(sub(q.position[0], stop_pos));
      out.final_w = norm(q.angular_velocity[0]);
      break;
    }
    if (stop_step < 0 && sim.steps() > limit) break;
  }
  for (size_t k = 2; k < peaks.size(); ++k)
    if (peaks[k - 1] > 0) out.growth = std::max(out.growth, peaks[k] / peaks[k - 1]);
  out.first_peak = peaks.size() > 1 ? peaks[1] : 0;
  out.energy_rise = energy.worst_rise;
  out.energy_tol = 8 * real_eps(prec) * scale;
  return out;
}

// Creep allowed over a hold window: in double the resting bead does not move
// at all (to the last bit) once the rocking has decayed; in float its
// position drifts by ~3e-14 R per step (the float force balance never
// cancels exactly): 1e-13 R per step.
double creep_bound(Precision p, std::int64_t hold) {
  return p == Precision::Double ? 1e-12 * kR : 1e-13 * kR * double(hold);
}

class RollingNearRest : public PrecisionTest {};

// Rolling: mu_s = 0.5, enough to roll without slipping (that needs
// mu_s > mu_r / (0.6 R) = 0.07 with the paper's mu_r): constant deceleration
// a = 5 mu_r g / (7 R).
TEST_P(RollingNearRest, RollingSphereStopsWithoutChatterAndHolds) {
  const Precision prec = GetParam();
  const double v0 = full_form() ? 3e-4 : 1e-4, mu_r = 5e-5;
  const double t_theory = v0 / (5 * mu_r * kG / (7 * kR));
  const std::int64_t hold = full_form() ? 1000000 : 50000;
  const RollOutcome r = roll_and_hold(prec, 0.5, v0, t_theory, hold);
  ASSERT_GT(r.t_stop, 0) << "did not stop within 1.5 x the constant-torque time";
  std::printf("[measure] %s, %s: sphere rolling at %.3g m/s (mu_s 0.5, mu_r %.3g m): stopped at "
              "%.6g s, constant torque %.6g s (%+.3f%%); %d sign changes of w_y after the stop, "
              "largest peak ratio %.3g (bound 1), first peak %.3g rad/s\n",
              form(), precision_name(prec), v0, mu_r, r.t_stop, t_theory,
              100 * (r.t_stop / t_theory - 1), r.sign_changes, r.growth, r.first_peak);
  std::printf("[measure] %s, %s: held %lld steps: centre moved %.3g m (%.3g R, bound %.3g R), "
              "final |w| %.3g rad/s; energy: largest rise %.3g J (round-off allowance %.3g J)\n",
              form(), precision_name(prec), static_cast<long long>(hold), r.creep, r.creep / kR,
              creep_bound(prec, hold) / kR, r.final_w, r.energy_rise, r.energy_tol);
  EXPECT_NEAR(r.t_stop / t_theory, 1.0, 0.05);
  EXPECT_LE(r.growth, 1.0) << "w_y changed sign with a growing amplitude";
  EXPECT_LE(r.creep, creep_bound(prec, hold));
  EXPECT_LE(r.energy_rise, r.energy_tol);
}

// The paper's pair, mu_s = 0.02 with mu_r = 5e-5 m: the rolling torque
// exceeds what friction can balance (mu_r > 0.6 mu_s R), so the spin stops
// first and the bead slides to rest at t = v0 / (mu_s g). While it slides
// the rolling torque must hold the spin at zero; the limiter, which sees the
// spin before the friction torque of the same step is added, lets at most
// one step of that torque through: |w| <= mu_s m g R dt / I.
TEST_P(RollingNearRest, SlidingSphereKeepsItsSpinStopped) {
  const Precision prec = GetParam();
  const double v0 = full_form() ? 3e-4 : 1e-4, mu_s = 0.02;
  const double t_theory = v0 / (mu_s * kG);
  const std::int64_t hold = full_form() ? 1000000 : 50000;
  const RollOutcome r = roll_and_hold(prec, mu_s, v0, t_theory, hold);
  ASSERT_GT(r.t_stop, 0);
  Simulation probe(default_device(), sphere_on_floor(prec, glass(0.87, mu_s, 5e-5), kR, v0));
  const double w_step = mu_s * kG * kR * probe.dt() / (0.4 * kR * kR);
  std::printf("[measure] %s, %s: sphere at %.3g m/s, paper's mu_s 0.02: stopped at %.6g s, "
              "sliding theory %.6g s (%+.3f%%); spin while sliding %.3g rad/s (one step of the "
              "friction torque: %.3g rad/s); peak ratio %.3g; held %lld steps: moved %.3g R; "
              "energy rise %.3g J (allowance %.3g J)\n",
              form(), precision_name(prec), v0, r.t_stop, t_theory,
              100 * (r.t_stop / t_theory - 1), r.spin_while_sliding, w_step, r.growth,
              static_cast<long long>(hold), r.creep / kR, r.energy_rise, r.energy_tol);
  EXPECT_NEAR(r.t_stop / t_theory, 1.0, 0.05);
  EXPECT_LE(r.spin_while_sliding, 1.05 * w_step);
  EXPECT_LE(r.growth, 1.0);
  EXPECT_LE(r.creep, creep_bound(prec, hold));
  EXPECT_LE(r.energy_rise, r.energy_tol);
}

SIMSOLS_BOTH_PRECISIONS(RollingNearRest);

// Settled pile: a square pyramid of the paper's glass beads (3 x 3, 2 x 2
// in the hollows, 1 on top; 14 beads) in a box whose walls hold the base,
// with the paper's mu_s 0.02 and mu_r. It is statically stable and settles
// (sinks by its Hertz overlaps) within a few milliseconds. Then, over a
// long window:
//   chatter  no bead's angular velocity flips sign from one step to the
//            next and back at the next, with |w| above 1e-6 rad/s (a bead's
//            several rolling torques used to overshoot together and flip
//            every spin every step, see forces.cl). A single reversal is a
//            spin crossing zero: in float, round-off rocks the settled beads
//            at up to 7e-4 rad/s, and watched every step their spins cross
//            zero a few times in 40 000 steps at 2-8e-6 rad/s, smoothly;
//   creep    no bead moves by more than its weight's Hertz overlap over the
//            second half of the window;
//   energy   kinetic + gravitational + elastic (normal and tangential)
//            never rises above its lowest earlier value by more than the
//            round-off of the sum.
// (A random pour of 45 beads, tried first, had not finished collapsing
// after 0.15 s: beads still moved 0.4-0.75 mm; it measures settling, not
// stability at rest.)
Scene pyramid_scene(Precision prec) {
  Scene s = empty_scene(prec, glass(0.87, 0.02, 5e-5));
  s.effects.gravity = {0, 0, -kG};
  const double d = 2 * kR, h = d / std::sqrt(2.0), L = 3 * d;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s.particles.push_back(sphere(kR, {kR + i * d, kR + j * d, kR}));
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      s.particles.push_back(sphere(kR, {d + i * d, d + j * d, kR + h + 1e-9}));
  s.particles.push_back(sphere(kR, {1.5 * d, 1.5 * d, kR + 2 * h + 2e-9}));
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), plane("x0", {0, 0, 0}, {1, 0, 0}),
             plane("x1", {L, 0, 0}, {-1, 0, 0}), plane("y0", {0, 0, 0}, {0, 1, 0}),
             plane("y1", {0, L, 0}, {0, -1, 0})};
  return s;
}

class SettledPile : public PrecisionTest {};

TEST_P(SettledPile, NeitherChattersNorCreepsNorGainsEnergy) {
  const Precision prec = GetParam();
  const Scene scene = pyramid_scene(prec);
  Simulation sim(default_device(), scene);
  const double settle_time = 0.01;
  const std::int64_t window = full_form() ? 400000 : 40000;
  sim.advance(static_cast<std::int64_t>(settle_time / sim.dt()));
  const double ke_settled = sim.observe().kinetic();
  Monotone energy;
  double scale = 0;
  const std::int64_t every = 20;
  int flips = 0;
  double spin = 0, moved = 0;
  ParticleSnapshot mid, prev = sim.snapshot();
  for (std::int64_t k = 0; k < window; k += every) {
    sim.advance(every - 2);
    const ParticleSnapshot a = sim.snapshot();
    sim.advance(1);
    const ParticleSnapshot b = sim.snapshot();
    sim.advance(1);
    const ParticleSnapshot c = sim.snapshot();
    for (size_t i = 0; i < b.position.size(); ++i) {
      const double wa = norm(a.angular_velocity[i]), wb = norm(b.angular_velocity[i]);
      spin = std::max(spin, wa);
      if (dot(a.angular_velocity[i], b.angular_velocity[i]) < 0 &&
          dot(b.angular_velocity[i], c.angular_velocity[i]) < 0 && wa > 1e-6 && wb > 1e-6)
        ++flips;
    }
    energy.add(mechanical_energy(sim, &scale));
    if (k + every == window / 2) mid = c;
    if (k + every == window)
      for (size_t i = 0; i < c.position.size(); ++i)
        moved = std::max(moved, norm(sub(c.position[i], mid.position[i])));
  }
  const double d_w = resting_overlap(scene, scene.particles[0]);
  const double tol = 8 * real_eps(prec) * scale;
  std::printf("[measure] %s, %s: pyramid of %zu beads settled %.3g s (kinetic energy %.3g J); "
              "over the next %lld steps (%.3g s): %d spins above 1e-6 rad/s flipped twice in a row "
              "(largest |w| %.3g rad/s); largest bead displacement over the second half %.3g m "
              "(%.3g of the weight overlap %.3g m, bound 1); energy: largest rise %.3g J "
              "(round-off allowance %.3g J)\n",
              form(), precision_name(prec), scene.particles.size(), settle_time, ke_settled,
              static_cast<long long>(window), window * sim.dt(), flips, spin, moved, moved / d_w,
              d_w, energy.worst_rise, tol);
  EXPECT_EQ(flips, 0);
  EXPECT_LT(moved, d_w);
  EXPECT_LE(energy.worst_rise, tol);
}

SIMSOLS_BOTH_PRECISIONS(SettledPile);

// ===========================================================================
// Case 3a. Tangential history of a pair rotating rigidly.
//
// A free pair cannot stay in contact while it rotates (nothing attracts the
// beads), and confining walls would add their own contacts and forces. So
// the contact law itself (contact_law.cl, built from the solver's embedded
// sources with the solver's -D options and lane width) is driven by a small
// test kernel with the kinematics of a rigid rotation: constant overlap,
// the normal n turning about an axis a at a constant rate, the relative
// velocity of the contact points and the relative spin zero (both beads are
// points of one rigid body), and a spring preloaded to half the Coulomb
// limit. Over a full revolution:
//   - F_t stays in the tangent plane: |F_t . n| / |F_t| at round-off;
//   - |F_t| neither grows nor decays (the law keeps the spring's length);
//   - its direction is the initial one carried by the rotation, less the
//     spin about n (the law has no torsional spring: the spring is parallel
//     transported, turning by -(a . n) theta about n relative to the pair).
// Six axes: perpendicular to n (spring in and across the plane of rotation),
// 30 and 60 degrees off it, along n (pure twist), and a general one.
// ===========================================================================

const char* kRigidPairKernel = R"CL(
__kernel void rigid_pair(__global const real* normals, __global const real* spring0,
                         __global const real* coeff, __global real* force_out,
                         __global real* spring_out, real delta, real rstar, real mstar,
                         real istar, real dt, int steps, int m) {
  int idx[LANES], keep[LANES];
  if (!driver_lanes(m, idx, keep)) return;
  const PairLanes c = driver_pair(coeff);
  v3 sp = gather3(spring0, idx);
  lane dash = (lane)0;  // no record: a contact that began overlapped, in equilibrium
  for (int s = 0; s < steps; ++s) {
    const v3 n = gather3(normals + (size_t)4 * m * s, idx);
    const ContactResult r = contact_law((lane)delta, n, v_zero(), v_zero(), (lane)rstar,
                                        (lane)mstar, (lane)istar, c, dt, &sp, &dash);
    scatter4(force_out + (size_t)4 * m * s, idx, keep, r.force, (lane)0);
    scatter4(spring_out + (size_t)4 * m * s, idx, keep, sp, (lane)0);
  }
}
)CL";

Vec3 rotate(const Vec3& v, const Vec3& axis, double angle) {  // Rodrigues, unit axis
  const double c = std::cos(angle), s = std::sin(angle);
  const Vec3 k = cross(axis, v);
  const double kd = dot(axis, v) * (1 - c);
  return {v[0] * c + k[0] * s + axis[0] * kd, v[1] * c + k[1] * s + axis[1] * kd,
          v[2] * c + k[2] * s + axis[2] * kd};
}
Vec3 unit(const Vec3& v) { return scale(1 / norm(v), v); }

class RigidPairRotation : public PrecisionTest {};

TEST_P(RigidPairRotation, TangentialForceStaysInPlaneAndKeepsItsSize) {
  const Precision prec = GetParam();
  const bool dbl = prec == Precision::Double;
  Device& dev = *default_device();
  Scene scene = empty_scene(prec, glass(0.87, 0.3, 5e-5));  // friction, damping, rolling on
  scene.particles = {sphere(kR, {0, 0, 0}), sphere(kR, {2 * kR, 0, 0})};
  const KernelConfig config = make_kernel_config(scene, dev);
  const Program program(dev, config, law_driver_files({"rigid_pair.cl", kRigidPairKernel}));
  const Kernel kernel = program.kernel("rigid_pair");

  const Vec3 n0{1, 0, 0};
  const double tilt30 = std::numbers::pi / 6, tilt60 = std::numbers::pi / 3;
  struct Case { const char* name; Vec3 axis, spring_dir; };
  const std::vector<Case> cases = {
      {"axis perpendicular, spring in the plane of rotation", {0, 0, 1}, {0, 1, 0}},
      {"axis perpendicular, spring along the axis", {0, 0, 1}, {0, 0, 1}},
      {"axis 30 deg off n", {std::sin(tilt30), 0, std::cos(tilt30)}, {0, 1, 0}},
      {"axis 60 deg off n", {std::sin(tilt60), 0, std::cos(tilt60)}, {0, 0.6, 0.8}},
      {"axis along n (twist)", {1, 0, 0}, {0, 0.8, 0.6}},
      {"general axis", unit({1, 2, 3}), unit({0, 1, -1})}};
  const int m = static_cast<int>(cases.size());
  const int steps = full_form() ? 200000 : 20000;  // one revolution
  const double dtheta = 2 * std::numbers::pi / steps;

  const Material& g = scene.materials[0];
  const double estar = e_star(g);
  const double gstar = g.young_modulus / (2 * (1 + g.poisson_ratio)) / (2 * (2 - g.poisson_ratio));
  const double delta = 1e-3 * kR, rstar = kR / 2;
  const double mstar = mass(scene, scene.particles[0]) / 2;
  const double istar = 0.4 * mstar * 2 * kR * kR / 2;
  const double fn = 4.0 / 3.0 * estar * std::sqrt(rstar) * delta * std::sqrt(delta);
  const double kt = 8 * gstar * std::sqrt(rstar * delta);
  const double ft0 = 0.5 * g.sliding_friction * fn;  // half the Coulomb limit

  RealPacker normals(dbl), springs(dbl), coeff(dbl);
  for (int s = 0; s < steps; ++s)
    for (const Case& c : cases) {
      const Vec3 n = rotate(n0, c.axis, (s + 1) * dtheta);
      normals.put4(n[0], n[1], n[2], 0);
    }
  for (const Case& c : cases) {
    const Vec3 xi = scale(-ft0 / kt, unit(c.spring_dir));  // F_t = -k_t xi
    springs.put4(xi[0], xi[1], xi[2], 0);
  }
  const std::vector<double> k = driver_coefficients(scene);
  coeff.put4(k[0], k[1], k[2], k[3]);
  coeff.put4(k[4], k[5], k[6], k[7]);
  const size_t out_bytes = size_t(steps) * m * 4 * (dbl ? 8 : 4);
  ClMem nbuf = dev.alloc(normals.size(), normals.data());
  ClMem sbuf = dev.alloc(springs.size(), springs.data());
  ClMem cbuf = dev.alloc(coeff.size(), coeff.data());
  ClMem fout = dev.alloc(out_bytes), sout = dev.alloc(out_bytes);
  LawDriver driver(dev, config, kernel);
  for (const ClMem* b : {&nbuf, &sbuf, &cbuf, &fout, &sout}) driver.mem(*b);
  for (double v : {delta, rstar, mstar, istar, 1e-7}) driver.real(v);
  driver.integer(steps).integer(m).run(m);
  const size_t count = size_t(steps) * m * 4;
  const std::vector<double> F = driver.read(fout, count), XI = driver.read(sout, count);

  double worst_plane = 0, worst_spring_plane = 0, worst_grow = 0, worst_decay = 0, worst_dir = 0;
  for (int c = 0; c < m; ++c) {
    const Case& cs = cases[c];
    double plane = 0, spring_plane = 0, grow = 0, decay = 0, dir = 0;
    const Vec3 f0 = scale(ft0, unit(cs.spring_dir));
    for (int s = 0; s < steps; ++s) {
      const double theta = (s + 1) * dtheta;
      const Vec3 n = rotate(n0, cs.axis, theta);
      const size_t at = (size_t(s) * m + c) * 4;
      const Vec3 f{F[at], F[at + 1], F[at + 2]}, xi{XI[at], XI[at + 1], XI[at + 2]};
      const Vec3 ft = sub(f, scale(-fn, n));  // the Hertz normal force removed
      const double size = norm(ft);
      plane = std::max(plane, std::fabs(dot(ft, n)) / size);
      spring_plane = std::max(spring_plane, std::fabs(dot(xi, n)) / norm(xi));
      grow = std::max(grow, size / ft0 - 1);
      decay = std::max(decay, 1 - size / ft0);
      // expected: the initial force turned about n by -(a.n) theta, then carried by the pair
      const Vec3 expect = rotate(rotate(f0, n0, -dot(cs.axis, n0) * theta), cs.axis, theta);
      dir = std::max(dir, norm(sub(scale(1 / size, ft), scale(1 / ft0, expect))));
    }
    std::printf("[measure] %s, %s, %s: over one revolution in %d steps: |F_t.n|/|F_t| <= %.3g, "
                "|xi.n|/|xi| <= %.3g, |F_t| grew %.3g, decayed %.3g, direction off %.3g rad\n",
                form(), precision_name(prec), cs.name, steps, plane, spring_plane, grow, decay,
                dir);
    worst_plane = std::max(worst_plane, plane);
    worst_spring_plane = std::max(worst_spring_plane, spring_plane);
    worst_grow = std::max(worst_grow, grow);
    worst_decay = std::max(worst_decay, decay);
    worst_dir = std::max(worst_dir, dir);
  }
  const double eps = real_eps(prec);
  // F_t is recovered by removing the Hertz force computed here in double:
  // its round-off, eps x F_n = 100 eps x |F_t|, bounds the normal part.
  // The length is kept by a rescaling each step: at most one ulp of drift
  // per step. The direction follows the continuous transport to O(dtheta)
  // (each step projects along the chord of the normal's path).
  std::printf("[measure] %s, %s: bounds: plane %.3g, spring plane %.3g, size %.3g, direction "
              "%.3g rad\n",
              form(), precision_name(prec), 1000 * eps, 16 * eps, steps * eps,
              2 * dtheta + 1000 * eps);
  EXPECT_LE(worst_plane, 1000 * eps);
  EXPECT_LE(worst_spring_plane, 16 * eps);
  EXPECT_LE(worst_grow, steps * eps);
  EXPECT_LE(worst_decay, steps * eps);
  EXPECT_LE(worst_dir, 2 * dtheta + 1000 * eps);
}

SIMSOLS_BOTH_PRECISIONS(RigidPairRotation);

// ===========================================================================
// Case 3b. Contacts that break and re-form start from zero history.
//
// Two spinning beads in a closed channel, no gravity: they collide
// obliquely, fly apart, bounce off the end walls (frictional contacts that
// also break and re-form) and collide again, many times. Each contact ends with
// a loaded tangential spring (checked: the first contact carries a
// tangential force; its spring, which k_t ~ sqrt(d) hides as d -> 0, would
// dominate the one-step spring v_t dt of a new contact if it were kept). A stale spring would be carried
// into the next contact of the same pair, which stays in the neighbour list
// while the beads are apart. At the first step of each re-formed contact
// (bead-bead and bead-wall), the force must equal that of a fresh
// simulation started one step earlier from the same positions and
// velocities, which has no history at all: the same to 1e-9 relative in
// double, 1e-4 in float (the fresh float state is rebuilt from double
// positions: its last bit may differ).
// ===========================================================================
class ReformedContact : public PrecisionTest {};

Scene channel_scene(Precision prec, const std::vector<Particle>& beads) {
  Scene s = empty_scene(prec, glass(1.0, 0.3, 5e-5));  // elastic: they keep bouncing
  s.effects.gravity = {0, 0, 0};
  s.numerics.dt_fraction = 0.4;
  s.particles = beads;
  const double L = 6 * kR, W = 1.6 * kR;  // a closed channel: the beads cannot pass each other
  s.walls = {plane("x0", {-L, 0, 0}, {1, 0, 0}),  plane("x1", {L, 0, 0}, {-1, 0, 0}),
             plane("y0", {0, -W, 0}, {0, 1, 0}),  plane("y1", {0, W, 0}, {0, -1, 0}),
             plane("z0", {0, 0, -W}, {0, 0, 1}),  plane("z1", {0, 0, W}, {0, 0, -1})};
  return s;
}

// Force on `a` from `b` (b = -1 - wall for walls) in the last evaluation; 0 when none.
bool contact_force(Simulation& sim, int a, int b, Vec3* f) {
  for (const ContactForce& c : sim.contacts())
    if (c.a == a && c.b == b) {
      *f = c.force;
      return true;
    }
  return false;
}

TEST_P(ReformedContact, StartsFromZeroHistory) {
  const Precision prec = GetParam();
  const double v = 5, spin = 4000;
  const std::vector<Particle> start = {
      sphere(kR, {-2 * kR, 0, 0}, {v, 0.5, 0}, {0, 0, spin}),
      sphere(kR, {2 * kR, 0.4 * kR, 0}, {-v, -0.5, 0}, {spin, 0, -spin})};
  Simulation sim(default_device(), channel_scene(prec, start));
  // (pair or wall) -> touching on the previous step, contacts seen, checked
  struct Track {
    int a, b;
    const char* name;
    bool was = false;
    int contacts = 0, checked = 0;
    double first_tangential = 0;  // largest |F_t| during the first contact
    double worst = 0;            // largest relative difference to a fresh run
  };
  std::vector<Track> tracks = {{0, 1, "bead-bead"}, {0, -1, "bead 0 - wall x0"},
                               {1, -2, "bead 1 - wall x1"}};
  const double tol = prec == Precision::Double ? 1e-9 : 1e-4;
  const int wanted = full_form() ? 5 : 1;  // re-formed contacts checked per track
  const std::int64_t max_steps = 200000;
  std::int64_t steps = 0;
  ParticleSnapshot before = sim.snapshot();
  auto done = [&] {
    for (const Track& t : tracks)
      if (t.checked < wanted) return false;
    return true;
  };
  for (; steps < max_steps && !done(); ++steps) {
    sim.advance(1);
    for (Track& t : tracks) {
      Vec3 f{};
      const bool now = contact_force(sim, t.a, t.b, &f);
      if (now && !t.was) {
        ++t.contacts;
        if (t.contacts >= 2 && t.checked < wanted) {
          // a fresh simulation from the state one step earlier
          std::vector<Particle> beads = start;
          for (size_t i = 0; i < beads.size(); ++i) {
            beads[i].position = before.position[i];
            beads[i].velocity = before.velocity[i];
            beads[i].angular_velocity = before.angular_velocity[i];
          }
          Simulation fresh(default_device(), channel_scene(prec, beads));
          fresh.advance(1);
          Vec3 g{};
          ASSERT_TRUE(contact_force(fresh, t.a, t.b, &g)) << t.name;
          const double diff = norm(sub(f, g)) / norm(g);
          t.worst = std::max(t.worst, diff);
          EXPECT_LE(diff, tol) << t.name << ", contact " << t.contacts << " at step " << sim.steps();
          ++t.checked;
        }
      }
      if (now && t.contacts == 1) {
        // tangential part of the force (normal from the centres)
        const ParticleSnapshot q = sim.snapshot();
        Vec3 n = t.b >= 0 ? unit(sub(q.position[t.b], q.position[t.a]))
                          : Vec3{t.b == -1 ? -1.0 : 1.0, 0, 0};
        t.first_tangential = std::max(t.first_tangential, norm(sub(f, scale(dot(f, n), n))));
      }
      t.was = now;
    }
    before = sim.snapshot();
  }
  for (const Track& t : tracks) {
    std::printf("[measure] %s, %s, %s: %d contacts in %lld steps; |F_t| in the "
                "first contact up to %.3g N; first step of %d re-formed contacts vs a fresh run: largest "
                "difference %.3g (bound %.3g)\n",
                form(), precision_name(prec), t.name, t.contacts, static_cast<long long>(steps),
                t.first_tangential, t.checked, t.worst, tol);
    EXPECT_GE(t.checked, wanted) << t.name << ": the contact did not re-form often enough";
    EXPECT_GT(t.first_tangential, 0.01) << t.name << ": no tangential loading (test not sensitive)";
  }
}

SIMSOLS_BOTH_PRECISIONS(ReformedContact);

// ===========================================================================
// Case 5. Fast impacts: a bead at 10 m/s into a packed layer.
//
// A square layer of 5 x 5 glass beads (2.38 mm) resting on a floor, hit at
// 10 m/s from above: once head-on on the centre bead, once into the hollow
// between four beads (the hollow lets through only a sphere of 0.41 R). Every
// step: the impactor stays above the layer (its centre above the height at
// which it would rest in the hollow, 2.41 R, less the overlap allowance),
// no layer bead goes through the floor, and no overlap passes 5 % of the
// radius (Hertz theory for 10 m/s: 1.3 %). The solver's skin check (a
// particle beyond skin/2 since the last list build, flagged every step in
// integrate.cl, counted as State::late_builds) reports no violation. And it
// can fire: the same impact with a skin of 1e-7 m reports violations.
// ===========================================================================
class FastImpact : public PrecisionTest {};

Scene layer_scene(Precision prec, Vec3 aim, double skin) {
  Scene s = empty_scene(prec, glass(0.87, 0.3, 5e-5));
  s.effects.gravity = {0, 0, -kG};
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) s.particles.push_back(sphere(kR, {2 * kR * i, 2 * kR * j, kR}));
  s.particles.push_back(sphere(kR, {aim[0], aim[1], 4 * kR}, {0, 0, -10}));
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  s.numerics.skin = skin;
  return s;
}

struct ImpactResult {
  double lowest_impactor = INFINITY, lowest_layer = INFINITY, worst_overlap = 0, rebound = 0;
  std::int64_t late = 0;
};

ImpactResult impact(Precision prec, Vec3 aim, double skin, std::int64_t steps) {
  const Scene s = layer_scene(prec, aim, skin);
  Simulation sim(default_device(), s);
  ImpactResult r;
  const int imp = static_cast<int>(s.particles.size()) - 1;
  for (std::int64_t k = 0; k < steps; ++k) {
    sim.advance(1);
    const ParticleSnapshot q = sim.snapshot();
    r.lowest_impactor = std::min(r.lowest_impactor, q.position[imp][2]);
    for (int i = 0; i < imp; ++i) r.lowest_layer = std::min(r.lowest_layer, q.position[i][2]);
    for (int i = 0; i <= imp; ++i) {
      r.worst_overlap = std::max(r.worst_overlap, (q.radius[i] - q.position[i][2]) / kR);
      for (int j = i + 1; j <= imp; ++j)
        r.worst_overlap =
            std::max(r.worst_overlap, (2 * kR - norm(sub(q.position[i], q.position[j]))) / kR);
    }
    r.rebound = std::max(r.rebound, q.velocity[imp][2]);
  }
  r.late = sim.state().late_builds;
  return r;
}

TEST_P(FastImpact, NoTunnellingAndTheSkinCheckReports) {
  const Precision prec = GetParam();
  const std::int64_t steps = full_form() ? 20000 : 4000;  // the impact is over in ~100 steps
  struct Aim {
    const char* name;
    Vec3 at;
    double floor;  // lowest centre height allowed for the impactor
  } aims[] = {{"head-on", {0, 0, 0}, 3 * kR}, {"into the hollow", {kR, kR, 0}, (1 + std::sqrt(2.0)) * kR}};
  for (const Aim& a : aims) {
    const ImpactResult r = impact(prec, a.at, 0, steps);
    std::printf("[measure] %s, %s, %s at 10 m/s: impactor lowest %.4g R (bound %.4g R), layer "
                "lowest %.4g R, largest overlap %.3g R (bound 0.05 R), rebound %.3g m/s, skin "
                "violations %lld\n",
                form(), precision_name(prec), a.name, r.lowest_impactor / kR,
                a.floor / kR - 0.05, r.lowest_layer / kR, r.worst_overlap, r.rebound,
                static_cast<long long>(r.late));
    EXPECT_GT(r.lowest_impactor, a.floor - 0.05 * kR) << a.name;
    EXPECT_GT(r.lowest_layer, 0.95 * kR) << a.name;
    EXPECT_LT(r.worst_overlap, 0.05) << a.name;
    EXPECT_GT(r.rebound, 0) << a.name << ": no rebound";
    EXPECT_EQ(r.late, 0) << a.name;
  }
  const ImpactResult forced = impact(prec, {0, 0, 0}, 1e-7, 400);
  std::printf("[measure] %s, %s, skin 1e-7 m: %lld skin violations reported\n", form(),
              precision_name(prec), static_cast<long long>(forced.late));
  EXPECT_GT(forced.late, 0) << "the skin check never fired with a tiny skin";
}

SIMSOLS_BOTH_PRECISIONS(FastImpact);

}  // namespace
}  // namespace simsols::testing
