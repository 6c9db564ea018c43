// clumps.cl — stage: move clumps (move_clumps, after finish_particles).
//
// A clump is a rigid body of member spheres (scene.h, Clump). The member
// spheres take part in contacts as any sphere does (never with each
// other: the neighbour lists skip pairs of one clump, neighbors.cl), and
// finish_particles integrates them as if free; this stage then replaces
// that motion with the body's. One work item per clump:
//
//   F = sum f_i + M g,   T = sum (r_i x f_i + t_i),   r_i = q o_i q*
//   V_{n+1/2} = V_{n-1/2} + F/M dt,   L_{n+1/2} = L_{n-1/2} + T dt
//   X_{n+1}   = X_n + V_{n+1/2} dt                  (compensated in float)
//   q_{n+1}   = the free rotation of the body with angular momentum
//               L_{n+1/2} over dt
//
// with o_i a member's offset from the centroid in the body (principal)
// frame, q the body-to-scene unit quaternion, stored (x, y, z, w). The free
// rotation is the symplectic, time-reversible NO_SQUISH splitting (Miller
// et al., J. Chem. Phys. 116, 8649 (2002); Dullweber, Leimkuhler and
// McLachlan 1997): rotations about the principal axes x, y for dt/2, z for
// dt, y and x for dt/2, each exact for its axis (the body-frame momentum's
// other two components turn the opposite way). It keeps |L| to round-off
// and the energy within a bounded error; an asymmetric body shows the
// intermediate-axis instability (tests/solver/kernels/test_clumps.cpp).
// Members then take the body's motion: x_i = X + r_i, v_i = V + w x r_i,
// w_i = w = q (L_b / I) q*.
//
// Records: clump_inertia (M, I1, I2, I3) with the principal moments; the
// members of clump c are particles clump_members[c].x .. + .y - 1;
// body_offset[i] = (o_i, M of i's body): a free sphere's own mass, a
// member's clump's. The contact dashpots see the bodies' masses (forces.cl),
// the members' shares of M (vel.w) serve the observables.

INLINE real3 q_rotate(real4 q, real3 v) {
  const real3 t = cross(q.xyz, v) + q.w * v;
  return v + 2 * cross(q.xyz, t);
}

INLINE real4 q_mul(real4 a, real4 b) {
  real4 r;
  r.xyz = a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz);
  r.w = a.w * b.w - dot(a.xyz, b.xyz);
  return r;
}

// The body turned about its principal axis k by its momentum for h.
INLINE void turn_about(int k, real h, real4* q, real3* lb, real3 inertia) {
  const real ik = k == 0 ? inertia.x : (k == 1 ? inertia.y : inertia.z);
  const real lk = k == 0 ? (*lb).x : (k == 1 ? (*lb).y : (*lb).z);
  const real phi = lk / ik * h;
  // sine and cosine of the half angle: below 0.01 rad (every step of a
  // grain turning slower than ~0.01/dt) their Taylor polynomials, exact to
  // round-off there (the next terms are below 1e-17) and far cheaper than
  // the library's on CPUs; the full angle's from them
  const real x = phi / 2, x2 = x * x;
  real ch, sh;
  if (fabs(x) < (real)0.01) {
    sh = x * (1 - x2 / 6 * (1 - x2 / 20));
    ch = 1 - x2 / 2 * (1 - x2 / 12 * (1 - x2 / 30));
  } else {
    sh = sincos(x, &ch);
  }
  const real c = ch * ch - sh * sh, s = 2 * sh * ch;
  real4 r = (real4)(k == 0 ? sh : 0, k == 1 ? sh : 0, k == 2 ? sh : 0, ch);
  *q = q_mul(*q, r);
  real3 l = *lb;
  if (k == 0) l = (real3)(l.x, c * l.y + s * l.z, -s * l.y + c * l.z);
  if (k == 1) l = (real3)(c * l.x - s * l.z, l.y, s * l.x + c * l.z);
  if (k == 2) l = (real3)(c * l.x + s * l.y, -s * l.x + c * l.y, l.z);
  *lb = l;
}

// Rebuild and late flags of a member moved by the body (integrate.cl).
INLINE void member_moved(int i, real3 x, __global const float4* pos_build,
                         __global volatile int* flags, real skin) {
  const real3 moved = x - to_real3(pos_build[i].xyz);
  const real moved2 = dot(moved, moved);
  mark_travel(flags, moved2, skin);
}

__kernel void move_clumps(__global real4* pos, __global float4* pos_lo, __global real4* vel,
                          __global real4* omega, __global const real4* force,
                          __global const real4* torque, __global const float4* pos_build,
                          __global volatile int* flags, __global const real4* body_offset,
                          __global const real4* clump_inertia, __global const int2* clump_members,
                          __global real4* clump_pos, __global float4* clump_pos_lo,
                          __global real4* clump_quat, __global real4* clump_vel,
                          __global real4* clump_mom, real4 gravity, real dt, real skin,
                          int nclumps) {
  const int c = get_global_id(0);
  if (c >= nclumps) return;
  const real4 mi = clump_inertia[c];
  const int2 members = clump_members[c];
  real4 q = clump_quat[c];
  real3 f = (real3)(0, 0, 0), t = (real3)(0, 0, 0);
#ifdef HAS_GRAVITY
  f = mi.x * gravity.xyz;
#endif
  for (int i = members.x; i < members.x + members.y; ++i) {
    const real3 r = q_rotate(q, body_offset[i].xyz);
    const real3 fi = force[i].xyz;
    f += fi;
    t += cross(r, fi) + torque[i].xyz;
  }
  real4 v = clump_vel[c], l = clump_mom[c], x = clump_pos[c];
  v.xyz += f * (dt / mi.x);
  l.xyz += t * dt;
  DRIFT(&x, clump_pos_lo, c, v.xyz * dt);
  real3 lb = q_rotate((real4)(-q.xyz, q.w), l.xyz);
  turn_about(0, dt / 2, &q, &lb, mi.yzw);
  turn_about(1, dt / 2, &q, &lb, mi.yzw);
  turn_about(2, dt, &q, &lb, mi.yzw);
  turn_about(1, dt / 2, &q, &lb, mi.yzw);
  turn_about(0, dt / 2, &q, &lb, mi.yzw);
  q = normalize(q);
  const real3 w = q_rotate(q, lb / mi.yzw);
  clump_vel[c] = v;
  clump_mom[c] = l;
  clump_pos[c] = x;
  clump_quat[c] = q;
  for (int i = members.x; i < members.x + members.y; ++i) {
    const real3 r = q_rotate(q, body_offset[i].xyz);
    real4 xi = (real4)(x.xyz, pos[i].w);
#ifdef POS_COMPENSATED
    float4 xlo = clump_pos_lo[c];
    add_compensated(&xi, &xlo, r);
    pos_lo[i] = xlo;
#else
    xi.xyz += r;
#endif
    pos[i] = xi;
    vel[i] = (real4)(v.xyz + cross(w, r), vel[i].w);
    omega[i] = (real4)(w, omega[i].w);
    member_moved(i, xi.xyz, pos_build, flags, skin);
  }
}
