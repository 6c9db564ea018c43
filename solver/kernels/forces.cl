// forces.cl — stage: contact forces between particles.
//
// One work item handles LANES consecutive particles (one lane each) and
// gathers the forces of all their listed neighbours; pairs are computed from
// both sides (see contact_law.cl). Output per particle: force.xyz and
// force.w = number of touching neighbours; torque.xyz and torque.w = half the
// elastic energy of its contacts. Particle records: pos = (x, radius),
// vel = (v, mass), omega = (w, material).
//
// The lanes walk their lists in step: slot k of every lane at once, up to
// the longest list. A lane whose list is shorter, or whose neighbour does not
// touch, runs the law on stand-in values (half-overlapping spheres) and adds
// zero: no branches inside the SIMD arithmetic.

__kernel void contact_forces(__global const real* restrict pos POS_LO_SARG,
                             __global const real* restrict vel,
                             __global const real* restrict omega,
                             __global const int* restrict nbr_count,
                             __global const int* restrict nbr, __global real* restrict spring,
                             __global const real* restrict pairs, __global real* restrict force,
                             __global real* restrict torque,
                             real dt, int cap, int n, int nmat) {
  const int base = get_global_id(0) * LANES;
  if (base >= n) return;
  int ii[LANES], valid[LANES], len[LANES];
  int longest = 0;
  #pragma unroll
  for (int l = 0; l < LANES; ++l) {
    valid[l] = base + l < n;
    ii[l] = valid[l] ? base + l : n - 1;
    len[l] = valid[l] ? nbr_count[ii[l]] : 0;
    longest = max(longest, len[l]);
  }
  const LanePos pi = gather_pos(pos POS_LO_PASS, ii);
  const lane ri = gather(pos, ii, 3);
  const v3 vi = gather3(vel, ii);
  const lane mi = gather(vel, ii, 3);
  const v3 wi = gather3(omega, ii);
  const lane mat_i = gather(omega, ii, 3);
  const lane inertia_i = (real)0.4 * mi * ri * ri;
  real row_t[LANES];
  LANE_STORE(mat_i, row_t);

  v3 f = v_zero();
  v3 t = v_zero();
  lane e = (lane)0;
  lane touching = (lane)0;
  for (int k = 0; k < longest; ++k) {
    int jj[LANES], slot[LANES], listed[LANES], pair[LANES];
    #pragma unroll
    for (int l = 0; l < LANES; ++l) {
      listed[l] = k < len[l];
      slot[l] = NBR(ii[l], k, n, cap);
      jj[l] = listed[l] ? nbr[slot[l]] : ii[l];
    }
    const LanePos pj = gather_pos(pos POS_LO_PASS, jj);
    const v3 d = separation(pi, pj);
    const lane rj = gather(pos, jj, 3);
    const lane rsum = ri + rj;
    const lane d2 = v_dot(d, d);
    const lmask on = mask_of(listed) & (d2 < rsum * rsum) & (d2 > (real)0);
    const lane dist = SEL(on, sqrt(d2), (real)0.5 * rsum);
    const v3 nv = v_sel(on, v_mul(1 / dist, d), V3((lane)1, (lane)0, (lane)0));
    const lane delta = rsum - dist;
    const v3 vj = gather3(vel, jj);
    const lane mj = gather(vel, jj, 3);
    const v3 wj = gather3(omega, jj);
    real mat_j[LANES];
    LANE_STORE(gather(omega, jj, 3), mat_j);
    #pragma unroll
    for (int l = 0; l < LANES; ++l) pair[l] = (int)row_t[l] * nmat + (int)mat_j[l];
    const lane inertia_j = (real)0.4 * mj * rj * rj;
    const lane ai = ri - (real)0.5 * delta;  // lever arms to the common contact point
    const lane aj = rj - (real)0.5 * delta;
    const v3 vrel = v_sub(v_add(vi, v_cross(wi, v_mul(ai, nv))),
                          v_add(vj, v_cross(wj, v_neg(v_mul(aj, nv)))));
#ifdef HAS_FRICTION
    v3 sp = gather3(spring, slot);
#else
    v3 sp = v_zero();
#endif
    const ContactResult c = contact_law(delta, nv, vrel, v_sub(wi, wj), ai, ri * rj / rsum,
                                        mi * mj / (mi + mj),
                                        inertia_i * inertia_j / (inertia_i + inertia_j),
                                        gather_pairs(pairs, pair), dt, &sp);
#ifdef HAS_FRICTION
    // a contact that is lost ends its history
    int keep[LANES];
    #pragma unroll
    for (int l = 0; l < LANES; ++l) keep[l] = listed[l] && valid[l];
    scatter4(spring, slot, keep, v_sel(on, sp, v_zero()), (lane)0);
#endif
    f = v_add(f, v_sel(on, c.force, v_zero()));
    t = v_add(t, v_sel(on, c.torque, v_zero()));
    e += SEL(on, (real)0.5 * c.energy, (lane)0);
    touching += SEL(on, (lane)1, (lane)0);
  }
  scatter4(force, ii, valid, f, touching);
  scatter4(torque, ii, valid, t, e);
}
