// forces.cl — stage: contact forces between particles.
//
// One work item per particle gathers the forces of all its listed neighbours
// (pairs are computed from both sides, see contact_law.cl). Output per
// particle: force.xyz and force.w = number of touching neighbours;
// torque.xyz and torque.w = half the elastic energy of its contacts.
// Particle records: pos = (x, radius), vel = (v, mass), omega = (w, material).
// Non-touching list entries are skipped (they are most of a list with a
// generous skin); the law itself is branch-free (contact_law.cl).

__kernel void contact_forces(__global const real* restrict pos POS_LO_SARG,
                             __global const real* restrict vel,
                             __global const real* restrict omega,
                             __global const int* restrict nbr_count,
                             __global const int* restrict nbr, __global real* restrict spring,
                             __global const real* restrict pairs, __global real* restrict force,
                             __global real* restrict torque,
                             real dt, int cap, int n, int nmat) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const real ri = load_w(pos, i);
  const real mi = load_w(vel, i);
  const real ii = (real)0.4 * mi * ri * ri;
  const v3 vi = load3(vel, i);
  const v3 wi = load3(omega, i);
  const int row = (int)load_w(omega, i) * nmat;

  v3 f = v_zero();
  v3 t = v_zero();
  real e = 0;
  int touching = 0;
  const int len = nbr_count[i];
  for (int k = 0; k < len; ++k) {
    const int slot = NBR(i, k, n, cap);
    const int j = nbr[slot];
    const v3 d = REL3(i, j);
    const real rj = load_w(pos, j);
    const real rsum = ri + rj;
    const real d2 = v_dot(d, d);
    if (d2 >= rsum * rsum) {
#ifdef HAS_FRICTION
      store4(spring, slot, v_zero(), 0);  // contact lost: its history ends
#endif
      continue;
    }
    const real dist = sqrt(d2);
    const v3 nv = v_mul(1 / dist, d);
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
    store4(spring, slot, sp, 0);
#endif
    f = v_add(f, c.force);
    t = v_add(t, c.torque);
    e += (real)0.5 * c.energy;
    ++touching;
  }
  store4(force, i, f, (real)touching);
  store4(torque, i, t, e);
}
