// contact_law.cl — the paper's eq. (1), one contact at a time. Stateless
// except for the tangential spring passed in and out.
//
// Conventions: n is the unit normal from particle i towards its partner,
// delta > 0 the overlap, vrel the velocity of i's contact point relative to
// the partner's, wrel = w_i - w_partner. The returned force and torque act on
// i; the partner receives the opposite force and, for a sphere pair, the
// opposite torque when computed from its own side (the law is antisymmetric
// under i <-> j, which is what makes the per-particle gather conserve
// momentum).
//
//   normal   F_n = K_n d^{3/2} + gamma sqrt(m* K_n) d^{1/4} v_n, clamped >= 0
//            K_n = 4/3 E* sqrt(R*)
//   tangent  xi  <- xi rotated into the tangent plane, + v_t dt
//            F_t = -k_t xi - gamma sqrt(m* k_t) v_t,  k_t = 8 G* sqrt(R* d)
//            |F_t| > mu_s F_n  =>  F_t scaled to mu_s F_n, xi made consistent
//   rolling  M   = -min(mu_r F_n, I* |w_r| / dt) w_r / |w_r|,
//            w_r = wrel without its component along n
typedef struct {
  real3 force;   // on i
  real3 torque;  // on i, about its centre
  real energy;   // elastic normal energy 2/5 K_n d^{5/2}
  real fn;       // normal force magnitude
} ContactResult;

inline ContactResult contact_law(real delta, real3 n, real3 vrel, real3 wrel, real lever,
                                 real rstar, real mstar, real istar, real8 coef, real dt,
                                 real3* spring) {
  ContactResult out;
  const real sd = sqrt(delta);
  const real sqrt_r = sqrt(rstar);
  const real kn = (real)(4.0 / 3.0) * PAIR_ESTAR(coef) * sqrt_r;
  real fn = kn * delta * sd;
  out.energy = (real)0.4 * fn * delta;
  const real vn = dot(vrel, n);
#ifdef HAS_DAMPING
  fn += PAIR_GAMMA(coef) * sqrt(mstar * kn) * sqrt(sd) * vn;
  fn = fmax(fn, (real)0);
#endif
  out.fn = fn;
  out.force = -fn * n;
  out.torque = (real3)(0);

#ifdef HAS_FRICTION
  const real3 vt = vrel - vn * n;
  real3 xi = *spring;
  const real xi2 = dot(xi, xi);
  if (xi2 > (real)0) {  // rotate the stored spring into the current tangent plane
    xi -= dot(xi, n) * n;
    const real p2 = dot(xi, xi);
    xi = p2 > (real)0 ? xi * sqrt(xi2 / p2) : (real3)(0);
  }
  xi += vt * dt;
  const real kt = (real)8 * PAIR_GSTAR(coef) * sqrt_r * sd;
  real3 ft = -kt * xi;
#ifdef HAS_DAMPING
  const real ct = PAIR_GAMMA(coef) * sqrt(mstar * kt);
  ft -= ct * vt;
#else
  const real ct = 0;
#endif
  const real ftmax = PAIR_MUS(coef) * fn;
  const real ft2 = dot(ft, ft);
  if (ft2 > ftmax * ftmax) {  // sliding: Coulomb limit, spring rescaled to match
    ft *= ftmax / sqrt(ft2);
    xi = -(ft + ct * vt) / kt;
  }
  *spring = xi;
  out.force += ft;
  out.torque += cross(lever * n, ft);
#endif

#ifdef HAS_ROLLING
  const real3 wr = wrel - dot(wrel, n) * n;
  const real wm = length(wr);
  if (wm > (real)0) {
    // Constant torque mu_r F_n, but never more than what stops the relative
    // rolling within this step: no chatter around w_r = 0 and no creep.
    const real m = fmin(PAIR_MUR(coef) * fn, istar * wm / dt);
    out.torque -= (m / wm) * wr;
  }
#endif
  return out;
}
