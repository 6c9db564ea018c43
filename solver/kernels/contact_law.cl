// contact_law.cl — the paper's eq. (1), one contact at a time. Stateless
// except for the contact's history passed in and out (tangential spring,
// normal dashpot's record, elastic rolling torque). Branch-free (selects
// only) so that it vectorises across work items on CPUs, but for one
// uniform branch to the dashpot's exact treatment of a contact's ends.
//
// Conventions: n is the unit normal from particle i towards its partner,
// delta > 0 the overlap, vrel the velocity of i's contact point relative to
// the partner's, wrel = w_i - w_partner. The returned force acts on i, the
// partner receives exactly its opposite (the pair is computed once), and the
// torques are built from n x F_t and the rolling torque (see ContactResult),
// so linear and angular momentum are conserved to round-off.
//
//   normal   F_n = K_n d^{3/2} + gamma sqrt(m* K_n) d^{1/4} v_n, clamped >= 0
//            K_n = 4/3 E* sqrt(R*); the dashpot at the time level of the
//            positions (normal_force() below, docs/model.md)
//   tangent  xi  <- xi rotated into the tangent plane, + v_t dt
//            F_t = -k_t xi - gamma sqrt(m* k_t) v_t,  k_t = 8 G* sqrt(R* d)
//            |F_t| > mu_s F_n  =>  F_t scaled to mu_s F_n, xi = -F_t / k_t
//            mindlin_deresiewicz (HAS_MD_TANGENTIAL): the elastic force on
//            Mindlin & Deresiewicz's branches instead (md_elastic_force)
//   rolling  constant_torque (HAS_ROLLING), on the elastic F_n = K_n d^{3/2}:
//            M   = -min(mu_r F_n, I* |w_r| / dt) w_r / |w_r|,
//            w_r = wrel without its component along n
//            spring_dashpot (HAS_ROLLING_SPRING, Ai et al. 2011 model C):
//            M_k <- M_k rotated into the tangent plane - k_r w_r dt,
//            k_r = 2.25 mu_r^2 k_n (k_n = 2 E* sqrt(R* d), mu_r a length),
//            |M_k| <= mu_r F_n; M = M_k - eta_r 2 sqrt(I_r k_r) w_r while
//            |M_k| < mu_r F_n (I_r = 3.5 I*), |M| capped at mu_r F_n
//   cohesion capillary (HAS_CAPILLARY): capillary_force() below, a central
//            attraction between beads up to the rupture distance
//
// Each argument is a lane (one contact per lane, see common.cl). Pair
// coefficients come from the pair table, PAIR_RECORD reals per pair, its
// slots named in layout.h (PairSlot): E*, G*, gamma_n, mu_s, mu_r,
// sqrt(6 G*/E*), and with HAS_CAPILLARY gamma cos(theta), the liquid volume
// and the rupture distance.
// The torque on i about its centre is lever_i n x F_t + rolling; the
// partner (a sphere) receives lever_j n x F_t - rolling.
typedef struct {
  v3 force;        // on i
  v3 n_cross_ft;   // n x F_t
  v3 rolling;      // rolling-resistance torque on i
  lane energy;     // elastic normal energy 2/5 K_n d^{5/2}
} ContactResult;

// A particle's contacts summed (pair_forces, wall_contacts): force, torque,
// energy (half of each pair contact's, all of a wall contact's) and the
// number of contacts.
typedef struct {
  v3 f, t;
  lane e, touching;
} ContactSums;

INLINE ContactSums no_contacts() {
  ContactSums s;
  s.f = v_zero();
  s.t = v_zero();
  s.e = (lane)0;
  s.touching = (lane)0;
  return s;
}

// A contact's history, as the sub-models compiled in keep it (the planes
// that carry it: "Per-contact history" below).
typedef struct {
  v3 sp;        // tangential: mindlin's spring xi, or mindlin_deresiewicz's elastic F_t
  lane dash;    // normal dashpot's record
  v3 rsp;       // elastic rolling torque
  v3 turn;      // mindlin_deresiewicz: F_t at the last turning point
  lane branch;  // mindlin_deresiewicz: 0 virgin loading, 1 a Masing branch
} History;

// A contact that has just begun.
INLINE History no_history() {
  History h;
  h.sp = v_zero();
  h.dash = (lane)0;
  h.rsp = v_zero();
  h.turn = v_zero();
  h.branch = (lane)0;
  return h;
}

// Coefficients of each lane's material pair (kt_ratio = sqrt(6 G*/E*)).
typedef struct {
  lane estar, gstar, gamma, mu_s, mu_r, kt_ratio;
#ifdef HAS_CAPILLARY
  lane cap_tension, cap_volume, cap_rupture;
#endif
} PairLanes;

INLINE PairLanes gather_pairs(__global const real* pairs, const int* pair, int nmat) {
  PairLanes c;
  if (nmat == 1) {  // one material: the same coefficients in every lane
    c.estar = (lane)pairs[PAIR_E_STAR];
    c.gstar = (lane)pairs[PAIR_G_STAR];
    c.gamma = (lane)pairs[PAIR_GAMMA_N];
    c.mu_s = (lane)pairs[PAIR_MU_S];
    c.mu_r = (lane)pairs[PAIR_MU_R];
    c.kt_ratio = (lane)pairs[PAIR_KT_RATIO];
#ifdef HAS_CAPILLARY
    c.cap_tension = (lane)pairs[PAIR_CAP_TENSION];
    c.cap_volume = (lane)pairs[PAIR_CAP_VOLUME];
    c.cap_rupture = (lane)pairs[PAIR_CAP_RUPTURE];
#endif
    return c;
  }
  real t[PAIR_BASE_REALS][LANES];
  #pragma unroll
  for (int l = 0; l < LANES; ++l)
    for (int k = 0; k < PAIR_BASE_REALS; ++k) t[k][l] = pairs[PAIR_RECORD * pair[l] + k];
#ifdef HAS_CAPILLARY
  real u[PAIR_CAP_REALS][LANES];
  #pragma unroll
  for (int l = 0; l < LANES; ++l)
    for (int k = 0; k < PAIR_CAP_REALS; ++k) u[k][l] = pairs[PAIR_RECORD * pair[l] + PAIR_CAP_TENSION + k];
  c.cap_tension = LANE_LOAD(u[0]);  // u[k]: slot PAIR_CAP_TENSION + k
  c.cap_volume = LANE_LOAD(u[1]);
  c.cap_rupture = LANE_LOAD(u[2]);
#endif
  c.estar = LANE_LOAD(t[PAIR_E_STAR]);
  c.gstar = LANE_LOAD(t[PAIR_G_STAR]);
  c.gamma = LANE_LOAD(t[PAIR_GAMMA_N]);
  c.mu_s = LANE_LOAD(t[PAIR_MU_S]);
  c.mu_r = LANE_LOAD(t[PAIR_MU_R]);
  c.kt_ratio = LANE_LOAD(t[PAIR_KT_RATIO]);
  return c;
}

#ifdef HAS_CAPILLARY
// Liquid bridge between two beads at surface separation s (Rabinovich et
// al. 2005, eq. for two spheres with R = 2 R*, without the small sin(alpha)
// term):  F = 4 pi R* gamma cos(theta) / (1 + s / (2 d_sp)),
//         d_sp = s/2 (-1 + sqrt(1 + V / (pi R* s^2))),
// written as 4 pi R* gamma cos(theta) (1 - s / sqrt(s^2 + V / (pi R*))) so
// that s = 0 needs no limit. Overlapping beads (s < 0) feel F(0). Zero at
// and beyond the rupture distance (Lian et al. 1993). Returns |F| >= 0, an
// attraction along n.
INLINE lane capillary_force(lane s, lane rstar, PairLanes c) {
  const real pi = (real)3.14159265358979323846;
  const lane sp = fmax(s, (lane)0);
  const lane f = (real)4 * pi * rstar * c.cap_tension *
                 ((lane)1 - sp * rsqrt(sp * sp + c.cap_volume / (pi * rstar)));
  return SEL(s < c.cap_rupture, f, (lane)0);
}
#endif

#ifdef HAS_DAMPING
// Mean of d^{1/4} over the overlaps from lo to hi (both >= 0) along a straight
// path: 4/5 (hi^{5/4} - lo^{5/4}) / (hi - lo), written with s = lo^{1/4} and
// t = hi^{1/4} so that lo = hi needs no limit and close values do not cancel:
// 4/5 (t^4 + t^3 s + t^2 s^2 + t s^3 + s^4) / ((t + s)(t^2 + s^2)). 0 if both are 0.
INLINE lane mean_quarter_power(lane s, lane t) {
  const lane s2 = s * s, t2 = t * t;
  const lane num = t2 * t2 + t * s * (t2 + s2) + s2 * (t2 + s2);
  const lane den = (t + s) * (t2 + s2);
  return SEL(den > (real)0, (real)0.8 * num / fmax(den, (real)1e-30), (lane)0);
}

// The normal force with the dashpot at the time level of the positions.
// Leapfrog has the overlap d at step n and the approach speeds u- = v_{n-1/2}
// (given) and u+ = v_{n+1/2} (the result of this step). The dashpot
// gamma sqrt(m* K_n) d^{1/4} d' is the time derivative of
// 4/5 gamma sqrt(m* K_n) d^{5/4}, so its impulse over the step, from the
// overlap half a step back, a = d - u- dt/2, to half a step ahead,
// b = a + ubar dt, is exact given a and b:
//   F_n = K_n d^{3/2} + gamma sqrt(m* K_n) <d^{1/4}>_{a..b} ubar,  ubar = (u- + u+)/2.
// u+ = u- + o - dt F_n / m*: this contact's own force, implicitly, plus o, the
// change the rest of the world (other contacts, gravity) made to the
// approach speed in the last step, taken to persist: *record holds
// m* z, z = u- - dt F_n / m* of the last step (0: no contact then), and
// o = u- - z.
// Where the step's travel is small against the overlap (d >= 2 |u-| dt),
// <d^{1/4}> = d^{1/4} to 2e-3 and F_n is linear in ubar: one division. On
// the first and last steps of a contact the mean is taken exactly, and one
// Newton step from that estimate solves F_n(ubar) to round-off for any
// damping. On the first step (no record, and d <= u- dt) the impulse counts
// from the first touch (a = 0): the contact began within the last step,
// unseen, and o = 0. A contact without a record that began overlapped (a
// scene's initial packing) is taken to be in equilibrium for its first step:
// ubar = u-. Two bodies at rest in equilibrium (u- = 0, forces unchanged)
// get ubar = 0: no damping force.
typedef struct {
  lane fel, cn, back, lo, s;
  lmask interior;
} Dashpot;

// F_n for a trial ubar; *t receives b^{1/4} (the Newton slope is cn b^{1/4}).
INLINE lane dashpot_force(const Dashpot* d, lane ub, real dt, lane* t) {
  const lane b = d->back + ub * dt;
  const lane hi = fmax(b, (real)0);
  *t = sqrt(sqrt(hi));
  // mean rate of the overlap: ubar inside the contact, (b - a)/dt where it starts or ends
  const lane rate = SEL(d->interior & (b > (real)0), ub, (hi - d->lo) / dt);
  return d->fel + d->cn * mean_quarter_power(d->s, *t) * rate;
}

// F_n on the first and last steps of a contact, from the estimate ub. Not
// inlined: few contacts are at an edge in any step, and inlined, the code
// cost the whole contact stage ~8 % in float on PoCL even when not taken.
__attribute__((noinline)) lane dashpot_edge(lane fel, lane delta, lane vn, lane cn, lane hm,
                                            lane half_other, lmask first, lane ub, real dt) {
  Dashpot d;
  d.fel = fel;
  d.cn = cn;
  d.back = delta - (real)0.5 * dt * vn;
  d.lo = SEL(first, (lane)0, fmax(d.back, (real)0));
  d.s = sqrt(sqrt(d.lo));
  d.interior = !first & (d.back > (real)0);
  // one Newton step on g(ubar) = ubar - u- - o/2 + dt/(2 m*) F_n(ubar),
  // g' = 1 + dt/(2 m*) cn b^{1/4}
  lane t;
  const lane f0 = dashpot_force(&d, ub, dt, &t);
  const lane step = (ub - vn - half_other + hm * fmax(f0, (real)0)) /
                    (1 + SEL(f0 > (real)0, hm * cn * t, (lane)0));
  return dashpot_force(&d, ub - step, dt, &t);
}

INLINE lane normal_force(lane fel, lane delta, lane qd, lane vn, lane cn, lane mstar, real dt,
                         lane* record) {
  const lmask seen = *record != (real)0;
  // a first touch: no record, and d <= u- dt, no overlap a step back (1.5 u- dt
  // leaves room for round-off); not a contact that began overlapped, as in a
  // scene's initial packing, which is taken to be in equilibrium (ubar = u-)
  const lmask first = !seen & (delta < (real)1.5 * dt * vn);
  const lmask solved = seen | first;
  const lane m_vn = mstar * vn;
  const lane m_half_other = SEL(seen, (real)0.5 * (m_vn - *record), (lane)0);  // m* o / 2
  // ubar = u- + o/2 - dt/(2 m*) (fel + cn d^{1/4} ubar), times m*
  const lane ub = SEL(solved,
                      (m_vn + m_half_other - (real)0.5 * dt * fel) /
                          (mstar + (real)0.5 * dt * cn * qd),
                      vn);
  lane fn = fel + cn * qd * ub;
  const lmask edge = first | (delta < (real)2 * fabs(vn) * dt);
  if (mask_any(edge)) {
    const lane hm = (real)0.5 * dt / mstar;
    const lane exact = dashpot_edge(fel, delta, vn, cn, hm, m_half_other / mstar, first, ub, dt);
    fn = SEL(edge & solved, exact, fn);
  }
  fn = fmax(fn, (real)0);
  *record = m_vn - dt * fn;
  return fn;
}
#endif

// A stored spring (the tangential one, the elastic rolling torque) rotated
// into the current tangent plane, keeping its length.
INLINE v3 into_tangent_plane(v3 x, v3 n) {
  const real tiny = (real)1e-30;
  const lane x2 = v_dot(x, x);
  const v3 xp = v_sub(x, v_mul(v_dot(x, n), n));
  const lane p2 = v_dot(xp, xp);
  return v_mul(SEL(p2 > tiny, sqrt(x2 / fmax(p2, tiny)), (lane)0), xp);
}

#ifdef HAS_FRICTION
#ifdef HAS_MD_TANGENTIAL
// Mindlin & Deresiewicz (1953) micro-slip under a constant normal force P,
// followed step by step (Thornton 1991's branches): from F_t = 0 the virgin
// curve, then after each reversal a Masing branch from the turning point
// F_T, twice the virgin curve's size (Johnson 1985, section 7.2):
//   |F - F_T| = S [1 - (1 - s / s_max)^{3/2}],  s_max = 3 S / (2 k_t),
//   S = mu_s F_n (virgin) or 2 mu_s F_n (Masing), s the displacement along
// the branch. Each step converts |F - F_T| into s with the current S and
// k_t, adds |v_t| dt and returns to a force, so a branch is followed exactly
// whatever the step; the increment points along -v_t (F = -k xi). A step
// whose increment points back towards F_T is a reversal: F_T <- F.
// Returns the elastic force from the history's, `elastic`.
INLINE v3 md_elastic_force(v3 n, v3 vt, lane fn, lane kt, lane mu_s, real dt, v3 elastic,
                           v3* turn, lane* branch) {
  const real tiny = (real)1e-30;
  v3 f = into_tangent_plane(elastic, n);
  v3 t = into_tangent_plane(*turn, n);
  const v3 push = v_mul(-(lane)dt, vt);  // direction of the force's increment
  const lmask reverse = v_dot(push, v_sub(f, t)) < (real)0;
  t = v_sel(reverse, f, t);
  *branch = SEL(reverse, (lane)1, *branch);
  const v3 r = v_sub(f, t);
  const lane big_s = fmax(SEL(*branch > (real)0.5, (lane)2, (lane)1) * mu_s * fn, (lane)tiny);
  const lane s_max = (real)1.5 * big_s / fmax(kt, (lane)tiny);
  const lane r_len = sqrt(v_dot(r, r));
  const lane u = fmin(fmax((lane)1 - r_len / big_s, (lane)0), (lane)1);
  const lane s = s_max * ((lane)1 - cbrt(u * u));
  const lane ds = sqrt(v_dot(push, push));
  const lane w = fmax((lane)1 - fmin(s + ds, s_max) / s_max, (lane)0);
  const lane grow = fmax(big_s * ((lane)1 - w * sqrt(w)) - r_len, (lane)0);
  f = v_add(f, v_mul(grow / fmax(ds, (lane)tiny), push));
  *turn = t;
  return f;
}
#endif

// Coulomb's limit on the trial force: F_t scaled to mu_s F_n (ftmax) where
// it exceeds it; *sliding says where.
INLINE v3 coulomb_limit(v3 ft, lane ftmax, lmask* sliding) {
  const real tiny = (real)1e-30;
  const lane ft2 = v_dot(ft, ft);
  *sliding = ft2 > ftmax * ftmax;
  return v_mul(SEL(*sliding, ftmax * rsqrt(fmax(ft2, tiny)), (lane)1), ft);
}

// The tangential force F_t on i from the tangential velocity vt and the
// contact's history h; kt the spring's stiffness k_t = 8 G* a, ct its
// dashpot's coefficient (0 without damping). The elastic force is -k_t xi
// (mindlin: the spring xi carried into this step) or Mindlin &
// Deresiewicz's (mindlin_deresiewicz: the history holds that force);
// F_t is it less the dashpot's force, within Coulomb's limit. While the
// contact slides the elastic part alone is made to carry the friction
// force (the dashpot's share is dissipated, not stored): an early strongly
// damped step would otherwise store C_t v_t against the motion and push
// forwards once k_t outgrows C_t (docs/model.md).
INLINE v3 tangential_force(v3 n, v3 vt, lane fn, lane kt, lane ct, lane mu_s, real dt,
                           History* h) {
#ifdef HAS_MD_TANGENTIAL
  const v3 fel = md_elastic_force(n, vt, fn, kt, mu_s, dt, h->sp, &h->turn, &h->branch);
#else
  const v3 xi = v_add(into_tangent_plane(h->sp, n), v_mul((lane)dt, vt));
  const v3 fel = v_mul(-kt, xi);
#endif
  v3 ft = fel;
#ifdef HAS_DAMPING
  ft = v_sub(ft, v_mul(ct, vt));
#endif
  lmask sliding;
  ft = coulomb_limit(ft, mu_s * fn, &sliding);
#ifdef HAS_MD_TANGENTIAL
  h->sp = v_sel(sliding, ft, fel);
#else
  h->sp = v_sel(sliding, v_mul(-1 / kt, ft), xi);
#endif
  return ft;
}
#endif

#ifdef HAS_ROLLING
#ifdef HAS_ROLLING_SPRING
// The rolling torque on i from the rolling velocity wr (wrel without its
// component along n): Ai et al. (2011) model C, elastic-plastic
// spring-dashpot; the elastic torque M_k in *roll_spring. sqrt_r sd is
// sqrt(R* d).
INLINE v3 rolling_torque(v3 n, v3 wr, lane fn, lane istar, PairLanes c, lane sqrt_r, lane sd,
                         real dt, v3* roll_spring, real rolling_damping) {
  const real tiny2 = (real)1e-36;  // representable in float
  const lane mmax = c.mu_r * fn;
  const lane kr = (real)2.25 * c.mu_r * c.mu_r * (real)2 * c.estar * sqrt_r * sd;
  v3 mk = into_tangent_plane(*roll_spring, n);
  mk = v_sub(mk, v_mul(kr * dt, wr));
  const lane mk_len2 = v_dot(mk, mk);
  const lmask plastic = mk_len2 >= mmax * mmax;
  mk = v_mul(SEL(plastic, mmax * rsqrt(fmax(mk_len2, tiny2)), (lane)1), mk);
  *roll_spring = mk;
  const lane cr = SEL(plastic, (lane)0, rolling_damping * (real)2 * sqrt((real)3.5 * istar * kr));
  v3 m = v_sub(mk, v_mul(cr, wr));
  const lane m2 = v_dot(m, m);
  return v_mul(SEL(m2 > mmax * mmax, mmax * rsqrt(fmax(m2, tiny2)), (lane)1), m);
}
#else
// The rolling torque on i from the rolling velocity wr (wrel without its
// component along n): constant torque mu_r F_n, but never more than what
// stops the relative rolling within this step: no chatter around w_r = 0
// and no creep. (The spring-dashpot's history and parameters are unused.)
INLINE v3 rolling_torque(v3 n, v3 wr, lane fn, lane istar, PairLanes c, lane sqrt_r, lane sd,
                         real dt, v3* roll_spring, real rolling_damping) {
  const real tiny2 = (real)1e-36;  // representable in float
  const lane wr2 = v_dot(wr, wr);
  const lane inv_wm = rsqrt(fmax(wr2, tiny2));
  const lane m = fmin(c.mu_r * fn, istar * (wr2 * inv_wm) * (1 / dt));
  return v_mul(-SEL(wr2 > tiny2, m * inv_wm, (lane)0), wr);
}
#endif
#endif

INLINE ContactResult contact_law_h(lane delta, v3 n, v3 vrel, v3 wrel, lane rstar,
                                   lane mstar, lane istar, PairLanes c, real dt, History* h,
                                   real rolling_damping) {
  ContactResult out;
  const lane sd = sqrt(delta);
  const lane sqrt_r = sqrt(rstar);
  const lane kn = (real)(4.0 / 3.0) * c.estar * sqrt_r;
  const lane fel = kn * delta * sd;
  out.energy = (real)0.4 * fel * delta;
  const lane vn = v_dot(vrel, n);
#ifdef HAS_DAMPING
  const lane qd = sqrt(sd);              // d^{1/4}
  const lane cn = c.gamma * sqrt(mstar * kn);
  const lane fn = normal_force(fel, delta, qd, vn, cn, mstar, dt, &h->dash);
#else
  const lane fn = fel;
#endif
  out.force = v_mul(-fn, n);
  out.n_cross_ft = v_zero();
  out.rolling = v_zero();

#ifdef HAS_FRICTION
  const lane kt = (real)8 * c.gstar * sqrt_r * sd;
#ifdef HAS_DAMPING
  // gamma sqrt(m* k_t) = gamma sqrt(m* K_n) sqrt(k_t / K_n), k_t / K_n = 6 G*/E* sqrt(d)
  const lane ct = cn * c.kt_ratio * qd;
#else
  const lane ct = (lane)0;
#endif
  const v3 ft = tangential_force(n, v_sub(vrel, v_mul(vn, n)), fn, kt, ct, c.mu_s, dt, h);
  out.force = v_add(out.force, ft);
  out.n_cross_ft = v_cross(n, ft);
#endif

#ifdef HAS_ROLLING
  const v3 wr = v_sub(wrel, v_mul(v_dot(wrel, n), n));
  // its limit on the elastic normal force, as the paper's eq. (1): the
  // dashpot's share neither raises it on loading nor lowers it on unloading
  out.rolling = rolling_torque(n, wr, fel, istar, c, sqrt_r, sd, dt, &h->rsp, rolling_damping);
#endif
  return out;
}

// The law with the contact record only, the tangential spring and the
// normal dashpot's record (tests drive it directly); under spring_dashpot
// rolling it starts from an unloaded rolling spring.
INLINE ContactResult contact_law(lane delta, v3 n, v3 vrel, v3 wrel, lane rstar, lane mstar,
                                 lane istar, PairLanes c, real dt, v3* spring, lane* dashpot) {
  History h = no_history();
  h.sp = *spring;
  h.dash = *dashpot;
  const ContactResult r = contact_law_h(delta, n, vrel, wrel, rstar, mstar, istar, c, dt, &h,
                                        (real)0.3);
  *spring = h.sp;
  *dashpot = h.dash;
  return r;
}

// ---- Per-contact history ---------------------------------------------------
// The sub-models that keep state from one step to the next declare it here,
// beside their laws (LAMMPS GRANULAR's history slots). Each compiled one owns
// a plane, one record of 4 reals per contact, numbered by the host's table
// (cl_program.h, history_plane_table):
//   HIST_CONTACT (HAS_CONTACT_RECORD)  tangential = mindlin: the spring xi in
//                                      xyz; damping = viscous: the normal
//                                      dashpot's record in w
//   HIST_ROLL    (HAS_ROLLING_SPRING)  rolling = spring_dashpot: the elastic
//                                      rolling torque M_k in xyz
//   HIST_TURN    (HAS_MD_TANGENTIAL)   tangential = mindlin_deresiewicz: F_t
//                                      at the last turning point in xyz, the
//                                      branch (0 virgin, 1 Masing) in w; the
//                                      contact record's xyz then holds the
//                                      elastic F_t instead of xi
// The lists and the wall slots carry all HIST_PLANES planes without knowing
// what they hold (neighbors.cl, walls.cl); the loops that run the law load
// the records, turn them into a History and back with the two functions
// below, and store them (forces.cl, walls.cl).
#if defined(HAS_CONTACT_RECORD) && !defined(HIST_CONTACT)
#error "HIST_CONTACT: the contact record has no plane (cl_program.cpp, kHistoryPlanes)"
#endif
#if defined(HAS_MD_TANGENTIAL) && !defined(HIST_TURN)
#error "HIST_TURN: the turning point has no plane (cl_program.cpp, kHistoryPlanes)"
#endif
#if defined(HAS_ROLLING_SPRING) && !defined(HIST_ROLL)
#error "HIST_ROLL: the rolling spring has no plane (cl_program.cpp, kHistoryPlanes)"
#endif
// Records of every plane, at least one (a private array may not be empty).
#define HIST_RECORDS (HIST_PLANES > 0 ? HIST_PLANES : 1)

// The history in the planes' records as loaded (rec[p]: plane p's).
INLINE History history_from_planes(const Lane4* rec) {
  History h = no_history();
#ifdef HAS_CONTACT_RECORD
  h.sp = rec[HIST_CONTACT].xyz;
  h.dash = rec[HIST_CONTACT].w;
#endif
#ifdef HAS_ROLLING_SPRING
  h.rsp = rec[HIST_ROLL].xyz;
#endif
#ifdef HAS_MD_TANGENTIAL
  h.turn = rec[HIST_TURN].xyz;
  h.branch = rec[HIST_TURN].w;
#endif
  return h;
}

// The planes' records to store; a lane whose contact is lost (`on` false)
// ends its history (zeros).
INLINE void history_planes_of(History h, lmask on, Lane4* rec) {
#ifdef HAS_CONTACT_RECORD
  rec[HIST_CONTACT].xyz = v_sel(on, h.sp, v_zero());
  rec[HIST_CONTACT].w = SEL(on, h.dash, (lane)0);
#endif
#ifdef HAS_ROLLING_SPRING
  rec[HIST_ROLL].xyz = v_sel(on, h.rsp, v_zero());
  rec[HIST_ROLL].w = (lane)0;
#endif
#ifdef HAS_MD_TANGENTIAL
  rec[HIST_TURN].xyz = v_sel(on, h.turn, v_zero());
  rec[HIST_TURN].w = SEL(on, h.branch, (lane)0);
#endif
}
