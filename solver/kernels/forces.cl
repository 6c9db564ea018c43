// forces.cl — stage: contact forces between particles.
//
// One work item per particle gathers the forces of all its listed neighbours
// (pairs are computed from both sides, see contact_law.cl). Output per
// particle: force.xyz and force.w = number of touching neighbours;
// torque.xyz and torque.w = half the elastic energy of its contacts.
// Particle records: pos = (x, radius), vel = (v, mass), omega = (w, material).

__kernel void contact_forces(__global const real4* pos POS_LO_CARG,
                             __global const real4* vel, __global const real4* omega,
                             __global const int* nbr_count, __global const int* nbr,
                             __global real4* spring, __global const real8* pairs,
                             __global real4* force, __global real4* torque,
                             real dt, int cap, int n, int nmat) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const real4 pi = pos[i];
  const real4 vi = vel[i];
  const real4 wi = omega[i];
  const real ri = pi.w;
  const real mi = vi.w;
  const real ii = (real)0.4 * mi * ri * ri;
  const int row = (int)wi.w * nmat;

  real3 f = (real3)(0);
  real3 t = (real3)(0);
  real e = 0;
  int touching = 0;
  const int len = nbr_count[i];
  for (int k = 0; k < len; ++k) {
    const int slot = NBR(i, k, n, cap);
    const int j = nbr[slot];
    const real4 pj = pos[j];
    const real3 d = rel_pos(pi, pj LO(i) LO(j));
    const real rsum = ri + pj.w;
    const real d2 = dot(d, d);
    if (d2 >= rsum * rsum) {
#ifdef HAS_FRICTION
      spring[slot] = (real4)(0);  // contact lost: its history ends
#endif
      continue;
    }
    const real dist = sqrt(d2);
    const real3 nv = d / dist;
    const real delta = rsum - dist;
    const real4 vj = vel[j];
    const real4 wj = omega[j];
    const real rj = pj.w;
    const real mj = vj.w;
    const real ij = (real)0.4 * mj * rj * rj;
    const real ai = ri - (real)0.5 * delta;  // lever arms to the common contact point
    const real aj = rj - (real)0.5 * delta;
    const real3 vrel = (vi.xyz + cross(wi.xyz, ai * nv)) - (vj.xyz + cross(wj.xyz, -(aj * nv)));
    real3 sp = spring[slot].xyz;
    const ContactResult c = contact_law(delta, nv, vrel, wi.xyz - wj.xyz, ai, ri * rj / rsum,
                                        mi * mj / (mi + mj), ii * ij / (ii + ij),
                                        pairs[row + (int)wj.w], dt, &sp);
#ifdef HAS_FRICTION
    spring[slot] = (real4)(sp, 0);
#endif
    f += c.force;
    t += c.torque;
    e += (real)0.5 * c.energy;
    ++touching;
  }
  force[i] = (real4)(f, (real)touching);
  torque[i] = (real4)(t, e);
}
