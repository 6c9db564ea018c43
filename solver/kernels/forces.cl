// forces.cl — stage: contact forces between particles.
//
// One work item per particle gathers the forces of all its listed neighbours
// (pairs are computed from both sides, see contact_law.cl). Output per
// particle: force.xyz and force.w = number of touching neighbours;
// torque.xyz and torque.w = half the elastic energy of its contacts.
// Particle records: pos = (x, radius), vel = (v, mass), omega = (w, material).
//
// The neighbour loop has no branches, only selects: a slot that is past the
// end of the list, or not touching, runs the law on harmless stand-in values
// and contributes zero. With WG_UNIFORM_LOOP (CPUs) all work items of a group
// run the same number of iterations, each closed by a barrier, so PoCL
// vectorises every iteration across the work items.

__kernel void contact_forces(__global const real* restrict pos POS_LO_SARG,
                             __global const real* restrict vel,
                             __global const real* restrict omega,
                             __global const int* restrict nbr_count,
                             __global const int* restrict nbr, __global real* restrict spring,
                             __global const real* restrict pairs, __global real* restrict force,
                             __global real* restrict torque,
                             real dt, int cap, int n, int nmat) {
  // no early return: the uniform loop below has barriers
  const bool valid = get_global_id(0) < n;
  const int i = valid ? (int)get_global_id(0) : n - 1;
  const real ri = load_w(pos, i);
  const real mi = load_w(vel, i);
  const real ii = (real)0.4 * mi * ri * ri;
  const int row = (int)load_w(omega, i) * nmat;

  // Only scalars live across the barriers (PoCL keeps them per work item).
  real fx = 0, fy = 0, fz = 0, tx = 0, ty = 0, tz = 0;
  real e = 0;
  int touching = 0;
  const int len = valid ? nbr_count[i] : 0;
#ifdef WG_UNIFORM_LOOP
  __local int group_len;
  if (get_local_id(0) == 0) group_len = 0;
  barrier(CLK_LOCAL_MEM_FENCE);
  atomic_max(&group_len, len);
  barrier(CLK_LOCAL_MEM_FENCE);
  const int loop_len = group_len;
#else
  const int loop_len = len;
#endif
  for (int k = 0; k < loop_len; ++k) {
    const v3 vi = load3(vel, i);
    const v3 wi = load3(omega, i);
    const int slot = NBR(i, k, n, cap);
    const bool listed = k < len;
    const int j = listed ? nbr[slot] : i;
    const v3 d = REL3(i, j);
    const real rj = load_w(pos, j);
    const real rsum = ri + rj;
    const real d2 = v_dot(d, d);
    const bool on = listed && d2 < rsum * rsum && d2 > (real)0;
    // stand-in geometry for slots that do not touch: half-overlapping spheres
    const real dist = on ? sqrt(d2) : (real)0.5 * rsum;
    const v3 nv = on ? v_mul(1 / dist, d) : V3(1, 0, 0);
    const real delta = rsum - dist;
    const v3 vj = load3(vel, j);
    const real mj = load_w(vel, j);
    const v3 wj = load3(omega, j);
    const real ij = (real)0.4 * mj * rj * rj;
    const real ai = ri - (real)0.5 * delta;  // lever arms to the common contact point
    const real aj = rj - (real)0.5 * delta;
    const v3 vrel = v_sub(v_add(vi, v_cross(wi, v_mul(ai, nv))),
                          v_add(vj, v_cross(wj, v_neg(v_mul(aj, nv)))));
#ifdef HAS_FRICTION
    v3 sp = load3(spring, slot);
#else
    v3 sp = v_zero();
#endif
    const ContactResult c = contact_law(delta, nv, vrel, v_sub(wi, wj), ai, ri * rj / rsum,
                                        mi * mj / (mi + mj), ii * ij / (ii + ij), pairs,
                                        row + (int)load_w(omega, j), dt, &sp);
#ifdef HAS_FRICTION
    // a contact that is lost ends its history; slots past the list are unused
    // (padding work items write to the spare slots at the end of the buffer)
    store4(spring, valid ? slot : n * cap + k, v_select(on, sp, v_zero()), 0);
#endif
    fx += on ? c.force.x : (real)0;
    fy += on ? c.force.y : (real)0;
    fz += on ? c.force.z : (real)0;
    tx += on ? c.torque.x : (real)0;
    ty += on ? c.torque.y : (real)0;
    tz += on ? c.torque.z : (real)0;
    e += on ? (real)0.5 * c.energy : (real)0;
    touching += on ? 1 : 0;
#ifdef WG_UNIFORM_LOOP
    barrier(CLK_LOCAL_MEM_FENCE);
#endif
  }
  if (!valid) return;
  store4(force, i, V3(fx, fy, fz), (real)touching);
  store4(torque, i, V3(tx, ty, tz), e);
}
