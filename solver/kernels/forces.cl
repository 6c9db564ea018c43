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
// omega = (w, material); with clumps, body_offset = (offset, the body's
// mass), whose mass the dashpots see (body_mass).
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
                  int slot, size_t at, size_t plane, ContactSums* sum) {
  for (int p = 0; p < HIST_PLANES; ++p)
    store_slots(spring + 4 * (size_t)p * plane, at, v_zero(), (lane)0);
  store_shares(share, slot, v_neg(v_zero()), (lane)0, v_zero(), (lane)0);
  sum->f = v_add(sum->f, v_zero());
  sum->t = v_add(sum->t, v_zero());
  sum->e += (lane)0;
  sum->touching += (lane)0;
}

// The work item's particles, one per lane (past n, lanes stand in with the
// last particle and own no pairs), and the pairs each owns (the upper part
// of its list); returns the most pairs a lane owns.
INLINE int own_lanes(int base, int n, __global const int* restrict nbr_upper, int* ii, int* valid,
                     int* len) {
  int longest = 0;
#pragma unroll
  for (int l = 0; l < LANES; ++l) {
    valid[l] = base + l < n;
    ii[l] = valid[l] ? base + l : n - 1;
    len[l] = valid[l] ? nbr_upper[ii[l]] : 0;  // the pairs this particle owns
    longest = max(longest, len[l]);
  }
  return longest;
}

// What every contact of a lane's particle (i) needs of it (pair_forces,
// wall_contacts).
typedef struct {
  LanePos p;
  lane r, m, inertia;  // m: the body's mass (body_mass); inertia: the sphere's
  v3 v, w;
  real row[LANES];  // material: the particle's row of the pair table
#ifdef HAS_SHARED_ROLLING_CAP
  lane cap;  // the bead's part of the rolling cap's divisor
#endif
} Owner;

// The mass each lane's particle brings to a contact's dashpot: its body's
// (a clump member's is its whole clump's, as in LIGGGHTS' multisphere and
// PFC: the grain is what the contact stops; clumps.cl), else `own`, the
// particle's mass.
INLINE lane body_mass(__global const real* restrict body_offset, const int* ii, lane own) {
#ifdef HAS_CLUMPS
  return gather(body_offset, ii, 3);
#else
  return own;
#endif
}

// Each lane's particle's velocities, masses, inertia and material (and its
// part of the rolling cap's divisor), o->r already gathered.
INLINE void gather_motion(Owner* o, __global const real* restrict vel,
                          __global const real* restrict omega,
                          __global const real* restrict body_offset,
                          __global const int* restrict contacts_last, const int* ii) {
  const Lane4 vmi = gather4(vel, ii), wmi = gather4(omega, ii);
  o->v = vmi.xyz;
  o->w = wmi.xyz;
  o->m = body_mass(body_offset, ii, vmi.w);
  o->inertia = (real)0.4 * vmi.w * o->r * o->r;
  LANE_STORE(wmi.w, o->row);
#ifdef HAS_SHARED_ROLLING_CAP
  o->cap = cap_count(contacts_last, ii);
#endif
}

INLINE Owner gather_owner(__global const real* restrict pos POS_LO_SARG_FN,
                          __global const real* restrict vel, __global const real* restrict omega,
                          __global const real* restrict body_offset,
                          __global const int* restrict contacts_last, const int* ii) {
  Owner o;
  o.p = gather_pos(pos POS_LO_PASS, ii);
  o.r = gather(pos, ii, 3);
  gather_motion(&o, vel, omega, body_offset, contacts_last, ii);
  return o;
}

// Each lane's partner in slot q of its list (the upper slots from `slot`
// on, one per lane); a lane past its list stands in with its own particle.
INLINE void list_partners(int q, int slot, const int* len, const int* ii,
                          __global const int* restrict nbr, int* listed, int* jj) {
#pragma unroll
  for (int l = 0; l < LANES; ++l) {
    listed[l] = q < len[l];  // a lane past n lists nothing
    jj[l] = listed[l] ? nbr[slot + l] : ii[l];
  }
}

// Where each lane's partner lies: the separation d from i to it, its radius
// and the radii's sum, and whether the two touch (`on`).
typedef struct {
  v3 d;
  lane rj, rsum, d2;
  lmask on;
} PairGap;

INLINE PairGap pair_gap(__global const real* restrict pos POS_LO_SARG_FN, const Owner* o,
                        const int* jj, const int* listed, __global const real* restrict cell) {
  const Lane4 pr = gather4(pos, jj);
  LanePos pj;
  pj.hi = pr.xyz;
#ifdef POS_COMPENSATED
  pj.lo = gather4((__global const real*)pos_lo, jj).xyz;
#else
  pj.lo = v_zero();
#endif
  PairGap g;
  g.d = separation(o->p, pj);
#ifdef HAS_PERIODIC
  g.d = lane_min_image(cell, g.d);  // the nearest image of the partner (periodic.cl)
#endif
  g.rj = pr.w;
  g.rsum = o->r + g.rj;
  g.d2 = v_dot(g.d, g.d);
  g.on = mask_of(listed) & (g.d2 < g.rsum * g.rsum) & (g.d2 > (real)0);
  return g;
}

// The contact's normal (i towards its partner), overlap and lever arms from
// the centres to the common contact point; lanes that do not touch get the
// stand-in of half-overlapping spheres along x.
typedef struct {
  v3 nv;
  lane delta, ai, aj;
} PairContact;

INLINE PairContact pair_contact(PairGap g, lane ri) {
  const lane inv_dist = SEL(g.on, rsqrt(g.d2), 2 / g.rsum);
  const lane dist = SEL(g.on, g.d2 * inv_dist, (real)0.5 * g.rsum);
  PairContact k;
  k.nv = v_sel(g.on, v_mul(inv_dist, g.d), V3((lane)1, (lane)0, (lane)0));
  // >= 0: where the partners barely touch, d2 < rsum^2 can still give a
  // dist a rounding above rsum (rsqrt is not correctly rounded), and a
  // negative overlap would make the law's sqrt NaN
  k.delta = fmax(g.rsum - dist, (real)0);
  k.ai = ri - (real)0.5 * k.delta;  // lever arms to the common contact point
  k.aj = g.rj - (real)0.5 * k.delta;
  return k;
}

// Each lane's row of the pair table (materials of i and its partner); with
// one material the table has one row and `pair` is not read.
INLINE void pair_rows(const Owner* o, lane mat_j_lanes, int nmat, int* pair) {
  if (nmat > 1) {
    real mat_j[LANES];
    LANE_STORE(mat_j_lanes, mat_j);
#pragma unroll
    for (int l = 0; l < LANES; ++l) pair[l] = (int)o->row[l] * nmat + (int)mat_j[l];
  }
}

// Velocity of i's contact point relative to its partner's.
INLINE v3 contact_velocity(const Owner* o, v3 vj, v3 wj, PairContact k) {
  return v_sub(v_add(o->v, v_cross(o->w, v_mul(k.ai, k.nv))),
               v_add(vj, v_cross(wj, v_neg(v_mul(k.aj, k.nv)))));
}

// The pair's reduced moment of inertia, as the rolling cap sees it.
INLINE lane pair_istar(const Owner* o, lane mj, lane rj,
                       __global const int* restrict contacts_last, const int* jj) {
  const lane inertia_j = (real)0.4 * mj * rj * rj;
#ifdef HAS_SHARED_ROLLING_CAP
  // the constant torque's cap is shared among the contacts (see above)
  return o->inertia * inertia_j / (o->inertia + inertia_j) /
         fmax(o->cap, cap_count(contacts_last, jj));
#else
  return o->inertia * inertia_j / (o->inertia + inertia_j);
#endif
}

// The slots' history: every plane's records at `at` (by component,
// SLOT_REAL; plane p at 4 p `plane` reals), read as contact_law.cl says.
INLINE History load_history(__global const real* restrict spring, size_t at, size_t plane) {
  Lane4 rec[HIST_RECORDS];
  for (int p = 0; p < HIST_PLANES; ++p) rec[p] = load_slots(spring + 4 * (size_t)p * plane, at);
  return history_from_planes(rec);
}

// Lost contacts end their history (lanes not listed: padding, zeros).
INLINE void store_history(__global real* restrict spring, size_t at, size_t plane, lmask on,
                          History h) {
  Lane4 rec[HIST_RECORDS];
  history_planes_of(h, on, rec);
  for (int p = 0; p < HIST_PLANES; ++p)
    store_slots(spring + 4 * (size_t)p * plane, at, rec[p].xyz, rec[p].w);
}

#ifdef HAS_CAPILLARY
// The liquid bridge's force on i, towards its partner: listed pairs closer
// than the rupture distance, touching or not.
INLINE v3 bridge_force(PairGap g, const int* listed, lane rstar, PairLanes coef) {
  const lmask wet = mask_of(listed) & (g.d2 > (real)0) &
                    (g.d2 < (g.rsum + coef.cap_rupture) * (g.rsum + coef.cap_rupture));
  const lane inv_dw = rsqrt(fmax(g.d2, (real)1e-36));
  const lane fcap = SEL(wet, capillary_force(g.d2 * inv_dw - g.rsum, rstar, coef), (lane)0);
  return v_mul(fcap * inv_dw, g.d);
}
#endif

// The pair's outcome: i's force fi and its torque, contact flag and half the
// elastic energy into i's sums; the partner's share (-fi, its torque, the
// flag and the other half) into the slot's share record.
INLINE void add_pair(__global real* restrict share, int slot, lmask on, ContactResult c,
                     PairContact k, v3 fi, ContactSums* sum) {
  const lane half_e = SEL(on, (real)0.5 * c.energy, (lane)0);
  const lane flag = SEL(on, (lane)1, (lane)0);
  const v3 ti = v_sel(on, v_add(v_mul(k.ai, c.n_cross_ft), c.rolling), v_zero());
  const v3 tj = v_sel(on, v_sub(v_mul(k.aj, c.n_cross_ft), c.rolling), v_zero());
  // lanes not listed store zeros (fi, tj, flag and half_e are 0 there)
  store_shares(share, slot, v_neg(fi), flag, tj, half_e);
  sum->f = v_add(sum->f, fi);
  sum->t = v_add(sum->t, ti);
  sum->e += half_e;
  sum->touching += flag;
}

__kernel void pair_forces(__global const real* restrict pos POS_LO_SARG,
                          __global const real* restrict vel, __global const real* restrict omega,
                          __global const uint* restrict up_off, __global const int* restrict nbr,
                          __global const int* restrict nbr_upper, __global real* restrict spring,
                          __global const real* restrict pairs, __global real* restrict share,
                          __global real* restrict force, __global real* restrict torque,
                          __global const real* restrict body_offset,
                          __global const int* restrict contacts_last,
                          __global const real* restrict cell, real dt, real rolling_damping,
                          int stride, int n, int nmat) {
  const int base = get_global_id(0) * LANES;
  if (base >= n) return;
  int ii[LANES], valid[LANES], len[LANES];
  const int longest = own_lanes(base, n, nbr_upper, ii, valid, len);
  // the lanes lie in one slice (SLICE % LANES == 0), side by side; lanes
  // past n list nothing and store zeros into that slice's padding
  const int first = SLOT(up_off, base, 0);
  const Owner own = gather_owner(pos POS_LO_PASS, vel, omega, body_offset, contacts_last, ii);
  const size_t plane = (size_t)stride;  // records per history plane
  ContactSums sum = no_contacts();
  for (int q = 0; q < longest; ++q) {
    int jj[LANES], listed[LANES], pair[LANES];
    const int slot = first + q * SLICE;  // lane l's: SLOT(up_off, base + l, q) = slot + l
    const size_t at = SLOT_REAL(slot, 0);  // its records' components (load_slots)
    list_partners(q, slot, len, ii, nbr, listed, jj);
    const PairGap g = pair_gap(pos POS_LO_PASS, &own, jj, listed, cell);
#ifndef HAS_CAPILLARY
    if (!mask_any(g.on)) {  // no lane touches: what the law would leave, without it
      apart(spring, share, slot, at, plane, &sum);
      continue;
    }
#endif
    const PairContact k = pair_contact(g, own.r);
    Lane4 vmj = gather4(vel, jj);
    const Lane4 wmj = gather4(omega, jj);
#ifdef HAS_PERIODIC
    // velocities are relative to the cell's flow (periodic.cl): the
    // partner's image at d moves at L d relative to the flow at i
    vmj.xyz = v_add(vmj.xyz, lane_apply(cell, CELL_GRAD, g.d));
#endif
    pair_rows(&own, wmj.w, nmat, pair);
    const PairLanes coef = gather_pairs(pairs, pair, nmat);
    const lane rstar = own.r * g.rj / g.rsum, mj = body_mass(body_offset, jj, vmj.w);
    History h = load_history(spring, at, plane);
    const ContactResult c = contact_law_h(
        k.delta, k.nv, contact_velocity(&own, vmj.xyz, wmj.xyz, k), v_sub(own.w, wmj.xyz), rstar,
        own.m * mj / (own.m + mj), pair_istar(&own, vmj.w, g.rj, contacts_last, jj), coef,
        dt, &h, rolling_damping);
    store_history(spring, at, plane, g.on, h);
#ifdef HAS_CAPILLARY
    const v3 fi = v_add(v_sel(g.on, c.force, v_zero()), bridge_force(g, listed, rstar, coef));
#else
    const v3 fi = v_sel(g.on, c.force, v_zero());
#endif
    add_pair(share, slot, g.on, c, k, fi, &sum);
  }
  scatter4(force, ii, valid, sum.f, sum.touching);
  scatter4(torque, ii, valid, sum.t, sum.e);
}

// Particle i's shares, asked for ahead of collect_one (PREFETCH_SHARES:
// CPUs, where finish_particles runs it for the particle two work items
// on). Each share is read once, by its partner, a launch after it was
// written: beyond the caches (hundreds of thousands of beads) every one is
// a miss, and a work item's few misses at a time would leave the cores
// waiting on memory. Only the timing changes, never a value.
INLINE void prefetch_shares(int i, int n, __global const int* restrict nbr_count,
                            __global const int* restrict nbr_upper,
                            __global const uint* restrict lo_off,
                            __global const int* restrict mirror,
                            __global const real4* restrict share) {
#ifdef PREFETCH_SHARES
  if (i >= n) return;
  const int lower = nbr_count[i] - nbr_upper[i];
  for (int k = 0; k < lower; ++k) __builtin_prefetch(&share[2 * mirror[SLOT(lo_off, i, k)]]);
#endif
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
