// contact_law.cl — the paper's eq. (1), one contact at a time. Stateless
// except for the tangential spring passed in and out. Branch-free (selects
// only) so that it vectorises across work items on CPUs.
//
// Conventions: n is the unit normal from particle i towards its partner,
// delta > 0 the overlap, vrel the velocity of i's contact point relative to
// the partner's, wrel = w_i - w_partner, lever the distance from i's centre
// to the contact point. The returned force and torque act on i; the partner
// receives the opposite force and, for a sphere pair, the opposite torque
// when computed from its own side (the law is antisymmetric under i <-> j,
// which is what makes the per-particle gather conserve momentum).
//
//   normal   F_n = K_n d^{3/2} + gamma sqrt(m* K_n) d^{1/4} v_n, clamped >= 0
//            K_n = 4/3 E* sqrt(R*)
//   tangent  xi  <- xi rotated into the tangent plane, + v_t dt
//            F_t = -k_t xi - gamma sqrt(m* k_t) v_t,  k_t = 8 G* sqrt(R* d)
//            |F_t| > mu_s F_n  =>  F_t scaled to mu_s F_n, xi made consistent
//   rolling  M   = -min(mu_r F_n, I* |w_r| / dt) w_r / |w_r|,
//            w_r = wrel without its component along n
//
// Pair coefficients are read from the pair table `pairs` (8 reals per pair):
//   [0] E*  [1] G*  [2] gamma_n  [3] mu_s  [4] mu_r
typedef struct {
  v3 force;     // on i
  v3 torque;    // on i, about its centre
  real energy;  // elastic normal energy 2/5 K_n d^{5/2}
} ContactResult;

#define PAIR(p, k) pairs[8 * (p) + (k)]

inline ContactResult contact_law(real delta, v3 n, v3 vrel, v3 wrel, real lever, real rstar,
                                 real mstar, real istar, __global const real* pairs, int pair,
                                 real dt, v3* spring) {
  ContactResult out;
  const real tiny = (real)1e-30;
  const real sd = sqrt(delta);
  const real sqrt_r = sqrt(rstar);
  const real kn = (real)(4.0 / 3.0) * PAIR(pair, 0) * sqrt_r;
  real fn = kn * delta * sd;
  out.energy = (real)0.4 * fn * delta;
  const real vn = v_dot(vrel, n);
#ifdef HAS_DAMPING
  const real gamma = PAIR(pair, 2);
  fn = fmax(fn + gamma * sqrt(mstar * kn) * sqrt(sd) * vn, (real)0);
#endif
  out.force = v_mul(-fn, n);
  out.torque = v_zero();

#ifdef HAS_FRICTION
  const v3 vt = v_sub(vrel, v_mul(vn, n));
  v3 xi = *spring;
  // rotate the stored spring into the current tangent plane, keeping its length
  const real xi2 = v_dot(xi, xi);
  const v3 xp = v_sub(xi, v_mul(v_dot(xi, n), n));
  const real p2 = v_dot(xp, xp);
  xi = v_mul(p2 > tiny ? sqrt(xi2 / fmax(p2, tiny)) : (real)0, xp);
  xi = v_add(xi, v_mul(dt, vt));
  const real kt = (real)8 * PAIR(pair, 1) * sqrt_r * sd;
  v3 ft = v_mul(-kt, xi);
#ifdef HAS_DAMPING
  const real ct = gamma * sqrt(mstar * kt);
  ft = v_sub(ft, v_mul(ct, vt));
#else
  const real ct = 0;
#endif
  const real ftmax = PAIR(pair, 3) * fn;
  const real ft2 = v_dot(ft, ft);
  const bool sliding = ft2 > ftmax * ftmax;  // Coulomb limit: scale, make the spring consistent
  ft = v_mul(sliding ? ftmax / sqrt(fmax(ft2, tiny)) : (real)1, ft);
  xi = v_select(sliding, v_mul(-1 / kt, v_add(ft, v_mul(ct, vt))), xi);
  *spring = xi;
  out.force = v_add(out.force, ft);
  out.torque = v_cross(v_mul(lever, n), ft);
#endif

#ifdef HAS_ROLLING
  const v3 wr = v_sub(wrel, v_mul(v_dot(wrel, n), n));
  const real wm = sqrt(v_dot(wr, wr));
  // Constant torque mu_r F_n, but never more than what stops the relative
  // rolling within this step: no chatter around w_r = 0 and no creep.
  const real m = fmin(PAIR(pair, 4) * fn, istar * wm / dt);
  out.torque = v_sub(out.torque, v_mul(wm > tiny ? m / wm : (real)0, wr));
#endif
  return out;
}
