// contact_law.cl — the paper's eq. (1), one contact at a time. Stateless
// except for the tangential spring passed in and out. Branch-free (selects
// only) so that it vectorises across work items on CPUs.
//
// Conventions: n is the unit normal from particle i towards its partner,
// delta > 0 the overlap, vrel the velocity of i's contact point relative to
// the partner's, wrel = w_i - w_partner. The returned force acts on i, the
// partner receives exactly its opposite (the pair is computed once), and the
// torques are built from n x F_t and the rolling torque (see ContactResult),
// so linear and angular momentum are conserved to round-off.
//
//   normal   F_n = K_n d^{3/2} + gamma sqrt(m* K_n) d^{1/4} v_n, clamped >= 0
//            K_n = 4/3 E* sqrt(R*)
//   tangent  xi  <- xi rotated into the tangent plane, + v_t dt
//            F_t = -k_t xi - gamma sqrt(m* k_t) v_t,  k_t = 8 G* sqrt(R* d)
//            |F_t| > mu_s F_n  =>  F_t scaled to mu_s F_n, xi made consistent
//   rolling  M   = -min(mu_r F_n, I* |w_r| / dt) w_r / |w_r|,
//            w_r = wrel without its component along n
//
// Each argument is a lane (one contact per lane, see common.cl). Pair
// coefficients come from the pair table (8 reals per pair):
//   [0] E*  [1] G*  [2] gamma_n  [3] mu_s  [4] mu_r  [5] sqrt(6 G*/E*)
// The torque on i about its centre is lever_i n x F_t + rolling; the
// partner (a sphere) receives lever_j n x F_t - rolling.
typedef struct {
  v3 force;        // on i
  v3 n_cross_ft;   // n x F_t
  v3 rolling;      // rolling-resistance torque on i
  lane energy;     // elastic normal energy 2/5 K_n d^{5/2}
} ContactResult;

// Coefficients of each lane's material pair (kt_ratio = sqrt(6 G*/E*)).
typedef struct { lane estar, gstar, gamma, mu_s, mu_r, kt_ratio; } PairLanes;

INLINE PairLanes gather_pairs(__global const real* pairs, const int* pair, int nmat) {
  PairLanes c;
  if (nmat == 1) {  // one material: the same coefficients in every lane
    c.estar = (lane)pairs[0];
    c.gstar = (lane)pairs[1];
    c.gamma = (lane)pairs[2];
    c.mu_s = (lane)pairs[3];
    c.mu_r = (lane)pairs[4];
    c.kt_ratio = (lane)pairs[5];
    return c;
  }
  real t[6][LANES];
  #pragma unroll
  for (int l = 0; l < LANES; ++l)
    for (int k = 0; k < 6; ++k) t[k][l] = pairs[8 * pair[l] + k];
  c.estar = LANE_LOAD(t[0]);
  c.gstar = LANE_LOAD(t[1]);
  c.gamma = LANE_LOAD(t[2]);
  c.mu_s = LANE_LOAD(t[3]);
  c.mu_r = LANE_LOAD(t[4]);
  c.kt_ratio = LANE_LOAD(t[5]);
  return c;
}

INLINE ContactResult contact_law(lane delta, v3 n, v3 vrel, v3 wrel, lane rstar,
                                 lane mstar, lane istar, PairLanes c, real dt, v3* spring) {
  ContactResult out;
  const real tiny = (real)1e-30;
  const lane sd = sqrt(delta);
  const lane sqrt_r = sqrt(rstar);
  const lane kn = (real)(4.0 / 3.0) * c.estar * sqrt_r;
  lane fn = kn * delta * sd;
  out.energy = (real)0.4 * fn * delta;
  const lane vn = v_dot(vrel, n);
#ifdef HAS_DAMPING
  const lane qd = sqrt(sd);              // d^{1/4}
  const lane cn = c.gamma * sqrt(mstar * kn);
  fn = fmax(fn + cn * qd * vn, (real)0);
#endif
  out.force = v_mul(-fn, n);
  out.n_cross_ft = v_zero();
  out.rolling = v_zero();

#ifdef HAS_FRICTION
  const v3 vt = v_sub(vrel, v_mul(vn, n));
  v3 xi = *spring;
  // rotate the stored spring into the current tangent plane, keeping its length
  const lane xi2 = v_dot(xi, xi);
  const v3 xp = v_sub(xi, v_mul(v_dot(xi, n), n));
  const lane p2 = v_dot(xp, xp);
  xi = v_mul(SEL(p2 > tiny, sqrt(xi2 / fmax(p2, tiny)), (lane)0), xp);
  xi = v_add(xi, v_mul((lane)dt, vt));
  const lane kt = (real)8 * c.gstar * sqrt_r * sd;
  v3 ft = v_mul(-kt, xi);
#ifdef HAS_DAMPING
  // gamma sqrt(m* k_t) = gamma sqrt(m* K_n) sqrt(k_t / K_n), k_t / K_n = 6 G*/E* sqrt(d)
  const lane ct = cn * c.kt_ratio * qd;
  ft = v_sub(ft, v_mul(ct, vt));
#else
  const lane ct = (lane)0;
#endif
  const lane ftmax = c.mu_s * fn;
  const lane ft2 = v_dot(ft, ft);
  const lmask sliding = ft2 > ftmax * ftmax;  // Coulomb limit: scale, make the spring consistent
  ft = v_mul(SEL(sliding, ftmax * rsqrt(fmax(ft2, tiny)), (lane)1), ft);
  xi = v_sel(sliding, v_mul(-1 / kt, v_add(ft, v_mul(ct, vt))), xi);
  *spring = xi;
  out.force = v_add(out.force, ft);
  out.n_cross_ft = v_cross(n, ft);
#endif

#ifdef HAS_ROLLING
  const v3 wr = v_sub(wrel, v_mul(v_dot(wrel, n), n));
  const lane wr2 = v_dot(wr, wr);
  const real tiny2 = (real)1e-36;  // representable in float
  const lane inv_wm = rsqrt(fmax(wr2, tiny2));
  // Constant torque mu_r F_n, but never more than what stops the relative
  // rolling within this step: no chatter around w_r = 0 and no creep.
  const lane m = fmin(c.mu_r * fn, istar * (wr2 * inv_wm) * (1 / dt));
  out.rolling = v_mul(-SEL(wr2 > tiny2, m * inv_wm, (lane)0), wr);
#endif
  return out;
}
