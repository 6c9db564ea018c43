// Tangential slot "mindlin_deresiewicz" against Mindlin & Deresiewicz's
// loading-unloading-reloading loop under a constant normal force P
// (Johnson 1985, Contact Mechanics, section 7.2; Masing's rule for the
// branches after a reversal):
//   loading    F = mu P [1 - (1 - d / d_m)^{3/2}],   d_m = 3 mu P / (16 G* a)
//   unloading  F = F* - 2 mu P [1 - (1 - (d* - d) / (2 d_m))^{3/2}]
//   reloading  F = -F* + 2 mu P [1 - (1 - (d + d*) / (2 d_m))^{3/2}]
// each held within |F| <= mu P (full sliding beyond), a = sqrt(R* delta),
// k_t = 8 G* a (so d_m = 3 mu P / (2 k_t)).
//
// The contact law itself (contact_law.cl, the solver's sources and -D
// options) is driven by a small kernel: a fixed overlap and normal (so P
// is constant), no damping, and an imposed tangential displacement from 0
// to +A, back to -A and again to +A. Two amplitudes: A with F* = 0.8 mu P
// (micro-slip only: a closed loop) and A = 1.5 d_m (full sliding at each
// end). The linear spring (tangential = "mindlin") is driven along the
// same paths and its departure from the loop printed: it has the same
// initial stiffness, no micro-slip and so no loop below sliding.
#include <CL/cl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/core/cl_program.h"
#include "solver/core/real_packer.h"
#include "solver/kernels/kernel_source.h"
#include "tests/support/law_driver.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

const char* kLoopKernel = R"CL(
__kernel void md_loop(__global const real* dxi, __global const real* coeff,
                      __global real* force_out, real delta, real rstar, real mstar,
                      real istar, real dt, int steps, int m) {
  int idx[LANES], keep[LANES];
  if (!driver_lanes(m, idx, keep)) return;
  const PairLanes c = driver_pair(coeff);
  History h = no_history();
  v3 n;
  n.x = (lane)1;
  n.y = (lane)0;
  n.z = (lane)0;
  for (int s = 0; s < steps; ++s) {
    const v3 d = gather3(dxi + (size_t)4 * m * s, idx);
    const ContactResult r = contact_law_h((lane)delta, n, v_mul((lane)(1 / dt), d), v_zero(),
                                          (lane)rstar, (lane)mstar, (lane)istar, c, dt, &h,
                                          (real)0);
    scatter4(force_out + (size_t)4 * m * s, idx, keep, r.force, (lane)0);
  }
}
)CL";

// Mindlin & Deresiewicz's force (resisting the displacement, so the force
// on the bead is its opposite) along the path 0 -> A -> -A -> A.
struct Loop {
  double mu_p, d_m, amplitude, k_t;
  double virgin(double d) const {
    return d >= d_m ? mu_p : mu_p * (1 - std::pow(1 - d / d_m, 1.5));
  }
  double masing(double x) const {  // twice the virgin curve, from a turning point
    return x >= 2 * d_m ? 2 * mu_p : 2 * mu_p * (1 - std::pow(1 - x / (2 * d_m), 1.5));
  }
  // branch 0 loading, 1 unloading, 2 reloading; d the displacement
  double force(int branch, double d) const {
    const double top = virgin(amplitude);
    if (branch == 0) return virgin(d);
    if (branch == 1) return std::max(top - masing(amplitude - d), -mu_p);
    return std::min(-top + masing(d + amplitude), mu_p);
  }
};

struct Path {
  std::vector<double> d;  // displacement after each step
  std::vector<int> branch;
};

Path loop_path(double amplitude, int per_amplitude) {
  Path p;
  const double step = amplitude / per_amplitude;
  // 0 -> A, A -> -A, -A -> A, exact multiples of the step
  for (int k = 1; k <= per_amplitude; ++k) {
    p.d.push_back(k * step);
    p.branch.push_back(0);
  }
  for (int k = 1; k <= 2 * per_amplitude; ++k) {
    p.d.push_back(amplitude - k * step);
    p.branch.push_back(1);
  }
  for (int k = 1; k <= 2 * per_amplitude; ++k) {
    p.d.push_back(-amplitude + k * step);
    p.branch.push_back(2);
  }
  return p;
}

// Runs the law of `scene` along each path (cases side by side); returns
// the y component of the force on the bead, [step][case].
std::vector<double> drive(const Scene& scene, const std::vector<Path>& paths, double delta,
                          double rstar, double mstar, double istar, double dt) {
  Device& dev = *default_device();
  const bool dbl = scene.numerics.precision == Precision::Double;
  const KernelConfig config = make_kernel_config(scene, dev);
  const Program program(dev, config, law_driver_files({"md_loop.cl", kLoopKernel}));
  const Kernel kernel = program.kernel("md_loop");
  const int m = static_cast<int>(paths.size());
  const int steps = static_cast<int>(paths[0].d.size());
  RealPacker dxi(dbl), coeff(dbl);
  for (int s = 0; s < steps; ++s)
    for (const Path& p : paths) dxi.put4(0, p.d[s] - (s ? p.d[s - 1] : 0), 0, 0);
  const std::vector<double> k = driver_coefficients(scene);
  coeff.put4(k[0], k[1], k[2], k[3]);
  coeff.put4(k[4], k[5], k[6], k[7]);
  const size_t out_bytes = size_t(steps) * m * 4 * (dbl ? 8 : 4);
  ClMem dbuf = dev.alloc(dxi.size(), dxi.data()), cbuf = dev.alloc(coeff.size(), coeff.data());
  ClMem fout = dev.alloc(out_bytes);
  LawDriver driver(dev, config, kernel);
  driver.mem(dbuf).mem(cbuf).mem(fout);
  for (double v : {delta, rstar, mstar, istar, dt}) driver.real(v);
  driver.integer(steps).integer(m).run(m);
  const std::vector<double> f = driver.read(fout, size_t(steps) * m * 4);
  std::vector<double> fy(size_t(steps) * m);
  for (size_t k = 0; k < fy.size(); ++k) fy[k] = f[4 * k + 1];
  return fy;
}

// Case c of the driven laws against the loop: the largest difference
// from it (of mu P), and the energy the unloading-reloading part
// dissipates; the linear spring's departure printed beside.
void check_loop(const Loop& loop, const std::vector<Path>& paths, size_t c,
                const std::vector<double>& md, const std::vector<double>& linear,
                int per_amplitude, Precision precision) {
  const size_t m = paths.size(), steps = paths[c].d.size();
  const Path& path = paths[c];
  double worst = 0, worst_linear = 0, area = 0, area_theory = 0;
  for (size_t s = 0; s < steps; ++s) {
    const double theory = loop.force(path.branch[s], path.d[s]);
    const double f = -md[s * m + c], fl = -linear[s * m + c];  // the force on the bead is -F
    worst = std::max(worst, std::fabs(f - theory) / loop.mu_p);
    worst_linear = std::max(worst_linear, std::fabs(fl - theory) / loop.mu_p);
    if (s > 0 && path.branch[s] > 0) {  // from +A down to -A and back (trapezoids)
      const double dd = path.d[s] - path.d[s - 1];
      const double f_before = -md[(s - 1) * m + c];
      area += 0.5 * (f + f_before) * dd;
      area_theory += 0.5 * (theory + loop.force(path.branch[s - 1], path.d[s - 1])) * dd;
    }
  }
  // the loop's energy in closed form below full sliding (Johnson 1985,
  // section 7.2): 9 mu^2 P^2 / (10 G* a) [1 - r^{5/3} - 5 F* / (6 mu P) (1 + r^{2/3})],
  // r = 1 - F* / (mu P), with G* a = k_t / 8
  const double top = loop.virgin(loop.amplitude) / loop.mu_p, r = 1 - top;
  const double closed = loop.amplitude < loop.d_m
                            ? 7.2 * loop.mu_p * loop.mu_p / loop.k_t *
                                  (1 - std::pow(r, 5.0 / 3) - 5 * top / 6 * (1 + std::pow(r, 2.0 / 3)))
                            : NAN;
  std::printf("[measure] amplitude %.3f d_m, %d steps per amplitude: largest |F - F_MD| / "
              "(mu P) %.3g (linear spring %.3g); energy of the unloading-reloading loop "
              "%.6g J (the same trapezoids on the theory %.6g J; closed form %.6g J)\n",
              loop.amplitude / loop.d_m, per_amplitude, worst, worst_linear, std::fabs(area),
              std::fabs(area_theory), closed);
  if (per_amplitude >= 400 && loop.amplitude < loop.d_m) {  // trapezoids' error 1e-5 at 400
    EXPECT_NEAR(std::fabs(area) / closed, 1, 1e-4);
  }
  // achieved: 1.6e-5 (float), 7e-15 (double); loop energy 3e-5, 1e-14
  const bool single = precision == Precision::Float;
  EXPECT_LT(worst, single ? 2e-4 : 1e-13) << "amplitude " << loop.amplitude / loop.d_m;
  EXPECT_NEAR(area / area_theory, 1, single ? 5e-4 : 1e-12);
  // the linear spring has the same initial stiffness but no micro-slip
  EXPECT_GT(worst_linear, 0.1) << "amplitude " << loop.amplitude / loop.d_m;
}

class MindlinDeresiewicz : public PrecisionTest {};

TEST_P(MindlinDeresiewicz, FollowsTheLoadingUnloadingReloadingLoop) {
  const double R = 1e-3, mu = 0.3;
  Scene scene = empty_scene(GetParam(), soft(1.0, mu, 0));  // no damping, no rolling
  scene.effects.tangential = TangentialModel::MindlinDeresiewicz;
  scene.particles = {sphere(R, {0, 0, 0}), sphere(R, {2 * R, 0, 0})};
  const Material& g = scene.materials[0];
  const double estar = e_star(g);
  const double gstar = g.young_modulus / (2 * (1 + g.poisson_ratio)) / (2 * (2 - g.poisson_ratio));
  const double rstar = R / 2, delta = 1e-3 * R;
  const double p = 4.0 / 3.0 * estar * std::sqrt(rstar) * delta * std::sqrt(delta);
  const double kt = 8 * gstar * std::sqrt(rstar * delta);
  const double d_m = 1.5 * mu * p / kt;
  const double mstar = mass(scene, scene.particles[0]) / 2, istar = 0.2 * mstar * R * R;
  // amplitudes: F* = 0.8 mu P (micro-slip), and 1.5 d_m (full sliding)
  const std::vector<double> amplitudes = {d_m * (1 - std::pow(0.2, 2.0 / 3.0)), 1.5 * d_m};
  const double dt = 1e-7;
  // 400 steps per amplitude, and 7: a branch is followed exactly whatever
  // the step (contact_law.cl)
  for (const int per_amplitude : {400, 7}) {
    std::vector<Path> paths;
    for (double a : amplitudes) paths.push_back(loop_path(a, per_amplitude));
    scene.effects.tangential = TangentialModel::MindlinDeresiewicz;
    const std::vector<double> md = drive(scene, paths, delta, rstar, mstar, istar, dt);
    scene.effects.tangential = TangentialModel::Mindlin;
    const std::vector<double> linear = drive(scene, paths, delta, rstar, mstar, istar, dt);
    for (size_t c = 0; c < paths.size(); ++c)
      check_loop(Loop{mu * p, d_m, amplitudes[c], kt}, paths, c, md, linear, per_amplitude,
                 GetParam());
  }
}

SIMSOLS_BOTH_PRECISIONS(MindlinDeresiewicz);

}  // namespace
}  // namespace simsols::testing
