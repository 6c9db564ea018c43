// reduce.cl — observables, summed per work group in a fixed order
// (deterministic); the host adds the group partials in double.
//
// reduce_observables, per particle, with v_n = v_{n+1/2} - a_n dt/2:
//   0 translational KE  1 rotational KE  2 elastic energy  3 contacts (x2 for pairs)
//   4..6 linear momentum  7..9 angular momentum about the scene origin
//   10 gravitational potential -m g.x   11 particles
// reduce_walls: per wall, the force the particles exert on it and the
// number of contacts.
#define NOBS 12

__kernel void reduce_observables(__global const real4* pos POS_LO_CARG,
                                 __global const real4* vel, __global const real4* omega,
                                 __global const real4* force, __global const real4* torque,
                                 __global real* partial, real4 gravity, real dt, int n,
                                 __local real* scratch) {
  const int i = get_global_id(0);
  const int l = get_local_id(0);
  const int size = get_local_size(0);
  real o[NOBS];
  for (int c = 0; c < NOBS; ++c) o[c] = 0;
  if (i < n) {
    const real4 x = pos[i];
    const real4 v4 = vel[i];
    const real4 w4 = omega[i];
    const real m = v4.w;
    const real inertia = (real)0.4 * m * x.w * x.w;
    real3 a = force[i].xyz / m;
#ifdef HAS_GRAVITY
    a += gravity.xyz;
#endif
    const real3 v = v4.xyz - (real)0.5 * dt * a;
    const real3 w = w4.xyz - (real)0.5 * dt * torque[i].xyz / inertia;
    // positions x_n (pos already holds x_{n+1})
    const real3 xn = x.xyz - dt * v4.xyz;
    o[0] = (real)0.5 * m * dot(v, v);
    o[1] = (real)0.5 * inertia * dot(w, w);
    o[2] = torque[i].w;
    o[3] = force[i].w;
    const real3 p = m * v;
    o[4] = p.x; o[5] = p.y; o[6] = p.z;
    const real3 L = cross(xn, p) + inertia * w;
    o[7] = L.x; o[8] = L.y; o[9] = L.z;
#ifdef HAS_GRAVITY
    o[10] = -m * dot(gravity.xyz, xn);
#endif
    o[11] = 1;
  }
  for (int c = 0; c < NOBS; ++c) scratch[c * size + l] = o[c];
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int s = size / 2; s > 0; s >>= 1) {
    if (l < s)
      for (int c = 0; c < NOBS; ++c) scratch[c * size + l] += scratch[c * size + l + s];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0)
    for (int c = 0; c < NOBS; ++c) partial[get_group_id(0) * NOBS + c] = scratch[c * size];
}

#ifdef HAS_WALLS
// One work item per chunk of `chunk` particles: the chunk's sums for every
// wall (walls.cl's wall_chunk_sums, in index order, deterministic).
// partial[w * chunks + c]; global size chunks.
__kernel void reduce_walls(__global const int* wall_near, __global const uint* wall_off,
                           __global const real4* wall_force, __global real4* partial,
                           __global const real4* pos, __global const real4* walls,
                           __global const real4* wall_point, __global const real4* wall_turn,
                           int n, int chunk, int chunks, int nwalls) {
  const int c = get_global_id(0);
  if (c < chunks)
    wall_chunk_sums(c, wall_near, wall_off, wall_force, partial, pos, walls, wall_point,
                    wall_turn, n, chunk, chunks, nwalls);
}
#endif
