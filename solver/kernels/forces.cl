// forces.cl — stage: contact forces between particles, in two passes.
//
// pair_forces: every pair is computed once, by its lower-index particle,
//   from the upper part of its list (partners j > i, neighbors.cl). The
//   particle keeps its own share in registers and leaves the partner's
//   share (the opposite force, a contact flag; its torque, half the elastic
//   energy: two real4 side by side) in the pair's slot of the share buffer.
// collect_one: every particle adds the shares waiting for it in the slots
//   of its lower partners (found through `mirror`, built with the lists); it
//   runs at the start of finish_particles (integrate.cl), the next launch.
// No atomics: the sums have a fixed order and runs are reproducible bit for
// bit. Output per particle: force.xyz and force.w = number of touching
// neighbours; torque.xyz and torque.w = half the elastic energy of its
// contacts. Particle records: pos = (x, radius), vel = (v, mass),
// omega = (w, material).
//
// The rolling torque of a contact is capped so that alone it would not
// reverse the relative rolling within a step (contact_law.cl); a bead with k
// contacts gets up to k such torques, which together overshoot and flip its
// spin every step (chatter in a packing). The cap is therefore shared: the
// inertia passed to the law is divided by the larger contact count of the
// two particles in the last step (`contacts_last`, State::touching, kept by integrate.cl).
//
// One work item handles LANES consecutive particles (one lane each). The
// lanes walk their lists in step, up to the longest; a lane past its list, or
// whose neighbour does not touch, runs the law on stand-in values
// (half-overlapping spheres) and adds zero: no branches in the arithmetic.

// A step of pair_forces in which no lane's pair touches: the history of
// every slot ends (zeros), the partners' shares are zero (the force as
// -0, as the law's path leaves it), and the sums get the +0 that path adds.
INLINE void apart(__global real* spring, __global real* share,
                  int slot, size_t at, size_t plane, v3* f, v3* t, lane* e,
                  lane* touching) {
#ifdef HAS_CONTACT_RECORD
  store_slots(spring, at, v_zero(), (lane)0);
#endif
#ifdef HAS_ROLLING_SPRING
  store_slots(spring + 4 * HIST_ROLL * plane, at, v_zero(), (lane)0);
#endif
  store_shares(share, slot, v_neg(v_zero()), (lane)0, v_zero(), (lane)0);
  *f = v_add(*f, v_zero());
  *t = v_add(*t, v_zero());
  *e += (lane)0;
  *touching += (lane)0;
}

__kernel void pair_forces(__global const real* restrict pos POS_LO_SARG,
                          __global const real* restrict vel, __global const real* restrict omega,
                          __global const uint* restrict up_off, __global const int* restrict nbr,
                          __global const int* restrict nbr_upper, __global real* restrict spring,
                          __global const real* restrict pairs, __global real* restrict share,
                          __global real* restrict force, __global real* restrict torque,
                          __global const int* restrict contacts_last, real dt,
                          real rolling_damping, int stride, int n, int nmat) {
  const int base = get_global_id(0) * LANES;
  if (base >= n) return;
  int ii[LANES], valid[LANES], len[LANES];
  int longest = 0;
#pragma unroll
  for (int l = 0; l < LANES; ++l) {
    valid[l] = base + l < n;
    ii[l] = valid[l] ? base + l : n - 1;
    len[l] = valid[l] ? nbr_upper[ii[l]] : 0;  // the pairs this particle owns
    longest = max(longest, len[l]);
  }
  // the lanes lie in one slice (SLICE % LANES == 0), side by side; lanes
  // past n list nothing and store zeros into that slice's padding
  const int first = SLOT(up_off, base, 0);
  const LanePos pi = gather_pos(pos POS_LO_PASS, ii);
  const lane ri = gather(pos, ii, 3);
  const Lane4 vmi = gather4(vel, ii), wmi = gather4(omega, ii);
  const v3 vi = vmi.xyz, wi = wmi.xyz;
  const lane mi = vmi.w;
  const lane inertia_i = (real)0.4 * mi * ri * ri;
  real row_t[LANES];
  LANE_STORE(wmi.w, row_t);
#if defined(HAS_ROLLING) && !defined(HAS_ROLLING_SPRING)
  const lane cap_i = cap_count(contacts_last, ii);  // the bead's part of the divisor
#endif

  const size_t plane = (size_t)stride;  // records per history plane
  v3 f = v_zero();
  v3 t = v_zero();
  lane e = (lane)0;
  lane touching = (lane)0;
  for (int q = 0; q < longest; ++q) {
    int jj[LANES], listed[LANES], pair[LANES];
    const int slot = first + q * SLICE;  // lane l's: SLOT(up_off, base + l, q) = slot + l
    const size_t at = SLOT_REAL(slot, 0);  // its records' components (load_slots)
#pragma unroll
    for (int l = 0; l < LANES; ++l) {
      listed[l] = q < len[l];  // a lane past n lists nothing
      jj[l] = listed[l] ? nbr[slot + l] : ii[l];
    }
    const Lane4 pr = gather4(pos, jj);
    LanePos pj;
    pj.hi = pr.xyz;
#ifdef POS_COMPENSATED
    pj.lo = gather4((__global const real*)pos_lo, jj).xyz;
#else
    pj.lo = v_zero();
#endif
    const v3 d = separation(pi, pj);
    const lane rj = pr.w;
    const lane rsum = ri + rj;
    const lane d2 = v_dot(d, d);
    const lmask on = mask_of(listed) & (d2 < rsum * rsum) & (d2 > (real)0);
#ifndef HAS_CAPILLARY
    if (!mask_any(on)) {  // no lane touches: what the law would leave, without it
      apart(spring, share, slot, at, plane, &f, &t, &e, &touching);
      continue;
    }
#endif
    const lane inv_dist = SEL(on, rsqrt(d2), 2 / rsum);
    const lane dist = SEL(on, d2 * inv_dist, (real)0.5 * rsum);
    const v3 nv = v_sel(on, v_mul(inv_dist, d), V3((lane)1, (lane)0, (lane)0));
    const lane delta = rsum - dist;
    const Lane4 vmj = gather4(vel, jj), wmj = gather4(omega, jj);
    const v3 vj = vmj.xyz, wj = wmj.xyz;
    const lane mj = vmj.w;
    if (nmat > 1) {
      real mat_j[LANES];
      LANE_STORE(wmj.w, mat_j);
#pragma unroll
      for (int l = 0; l < LANES; ++l) pair[l] = (int)row_t[l] * nmat + (int)mat_j[l];
    }
    const lane inertia_j = (real)0.4 * mj * rj * rj;
    const lane ai = ri - (real)0.5 * delta;  // lever arms to the common contact point
    const lane aj = rj - (real)0.5 * delta;
    const v3 vrel = v_sub(v_add(vi, v_cross(wi, v_mul(ai, nv))),
                          v_add(vj, v_cross(wj, v_neg(v_mul(aj, nv)))));
    // per-contact history: the planes the compiled slots declare (common.cl)
#ifdef HAS_CONTACT_RECORD
    const Lane4 record = load_slots(spring, at);
    v3 sp = record.xyz;
    lane dash = record.w;
#else
    v3 sp = v_zero();
    lane dash = (lane)0;
#endif
#ifdef HAS_ROLLING_SPRING
    v3 rsp = load_slots(spring + 4 * HIST_ROLL * plane, at).xyz;
#else
    v3 rsp = v_zero();
#endif
    const PairLanes coef = gather_pairs(pairs, pair, nmat);
    const lane rstar = ri * rj / rsum;
#if defined(HAS_ROLLING) && !defined(HAS_ROLLING_SPRING)
    // the constant torque's cap is shared among the contacts (see above)
    const lane istar = inertia_i * inertia_j / (inertia_i + inertia_j) /
                       fmax(cap_i, cap_count(contacts_last, jj));
#else
    const lane istar = inertia_i * inertia_j / (inertia_i + inertia_j);
#endif
    const ContactResult c = contact_law_h(delta, nv, vrel, v_sub(wi, wj), rstar,
                                          mi * mj / (mi + mj), istar, coef, dt, &sp, &dash,
                                          &rsp, rolling_damping);
#ifdef HAS_CONTACT_RECORD
    // lost contacts end their history (lanes not listed: padding, zeros)
    store_slots(spring, at, v_sel(on, sp, v_zero()), SEL(on, dash, (lane)0));
#endif
#ifdef HAS_ROLLING_SPRING
    store_slots(spring + 4 * HIST_ROLL * plane, at, v_sel(on, rsp, v_zero()), (lane)0);
#endif
#ifdef HAS_CAPILLARY
    // liquid bridge: listed pairs closer than the rupture distance, touching or not
    const lmask wet = mask_of(listed) & (d2 > (real)0) &
                      (d2 < (rsum + coef.cap_rupture) * (rsum + coef.cap_rupture));
    const lane inv_dw = rsqrt(fmax(d2, (real)1e-36));
    const lane fcap = SEL(wet, capillary_force(d2 * inv_dw - rsum, rstar, coef), (lane)0);
    const v3 fbridge = v_mul(fcap * inv_dw, d);  // on i, towards its partner
#endif
    const lane half_e = SEL(on, (real)0.5 * c.energy, (lane)0);
    const lane flag = SEL(on, (lane)1, (lane)0);
#ifdef HAS_CAPILLARY
    const v3 fi = v_add(v_sel(on, c.force, v_zero()), fbridge);
#else
    const v3 fi = v_sel(on, c.force, v_zero());
#endif
    const v3 ti = v_sel(on, v_add(v_mul(ai, c.n_cross_ft), c.rolling), v_zero());
    const v3 tj = v_sel(on, v_sub(v_mul(aj, c.n_cross_ft), c.rolling), v_zero());
    // lanes not listed store zeros (fi, tj, flag and half_e are 0 there)
    store_shares(share, slot, v_neg(fi), flag, tj, half_e);
    f = v_add(f, fi);
    t = v_add(t, ti);
    e += half_e;
    touching += flag;
  }
  scatter4(force, ii, valid, f, touching);
  scatter4(torque, ii, valid, t, e);
}

INLINE void collect_one(int i, __global const int* restrict nbr_count,
                        __global const int* restrict nbr_upper,
                        __global const uint* restrict lo_off,
                        __global const int* restrict mirror,
                        __global const real4* restrict share,
                        __global real4* restrict force, __global real4* restrict torque) {
  real4 f = force[i];
  real4 t = torque[i];
  const int lower = nbr_count[i] - nbr_upper[i];
  for (int k = 0; k < lower; ++k) {
    const int slot = mirror[SLOT(lo_off, i, k)];
    f += share[2 * slot];  // the force record, then the torque record (store_shares)
    t += share[2 * slot + 1];
  }
  force[i] = f;
  torque[i] = t;
}
