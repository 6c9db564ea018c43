// walls.cl — stage: wall forces (infinite planes and finite rectangles).
//
// Same contact law as between spheres, with the wall as a body of infinite
// mass and radius (R* = r_i, m* = m_i, I* = I_i). Adds to the force/torque
// written by contact_forces. Each (wall, particle) slot w*n+i keeps its
// tangential spring and the force the particle exerts ON the wall, which
// reduce_walls sums into the wall's reaction.
// One work item handles LANES particles (see forces.cl).
// Wall records (4 x real4 per wall, see common.cl): [0] reference point and
// shape, [1] normal and material, [2] axis_u and half_u, [3] axis_v and half_v.
// Wall state: point/point_lo = current position of the reference point
// (moved by advance_walls), vel = its velocity.
#ifdef HAS_WALLS

__kernel void wall_forces(__global const real* restrict pos POS_LO_SARG,
                          __global const real* restrict vel, __global const real* restrict omega,
                          __global const real* restrict walls,
                          __global const real* restrict wall_point
#ifdef POS_COMPENSATED
                          , __global const float* restrict wall_point_lo
#endif
                          , __global const real* restrict wall_vel,
                          __global real* restrict wall_spring, __global real* restrict wall_force,
                          __global const real* restrict pairs, __global real* restrict force,
                          __global real* restrict torque, __global int* restrict wall_touch,
                          real dt, int n, int nwalls, int nmat) {
  const int base = get_global_id(0) * LANES;
  if (base >= n) return;
  int ii[LANES], valid[LANES], pair[LANES], was[LANES], now[LANES];
#pragma unroll
  for (int l = 0; l < LANES; ++l) {
    valid[l] = base + l < n;
    ii[l] = valid[l] ? base + l : n - 1;
    was[l] = valid[l] ? wall_touch[ii[l]] : 0;  // walls touched last step (bit w)
    now[l] = 0;
  }
  const LanePos pi = gather_pos(pos POS_LO_PASS, ii);
  const lane ri = gather(pos, ii, 3);
  const v3 vi = gather3(vel, ii);
  const lane mi = gather(vel, ii, 3);
  const v3 wi = gather3(omega, ii);
  real mat_i[LANES];
  LANE_STORE(gather(omega, ii, 3), mat_i);
  const lane inertia = (real)0.4 * mi * ri * ri;
  v3 f = gather3(force, ii);
  lane count = gather(force, ii, 3);
  v3 t = gather3(torque, ii);
  lane e = gather(torque, ii, 3);

  for (int w = 0; w < nwalls; ++w) {
    const int rec = 4 * WALL_RECORD * w;  // reals
    int slot[LANES];
    #pragma unroll
    for (int l = 0; l < LANES; ++l) slot[l] = w * n + ii[l];
    // d: from each particle centre to the wall's reference point
    LanePos wp;
    wp.hi = V3((lane)wall_point[4 * w], (lane)wall_point[4 * w + 1], (lane)wall_point[4 * w + 2]);
#ifdef POS_COMPENSATED
    wp.lo = V3((lane)wall_point_lo[4 * w], (lane)wall_point_lo[4 * w + 1],
               (lane)wall_point_lo[4 * w + 2]);
#else
    wp.lo = v_zero();
#endif
    const v3 d = separation(pi, wp);
    const v3 nrm = V3((lane)walls[rec + 4], (lane)walls[rec + 5], (lane)walls[rec + 6]);
    v3 to_wall;  // from the centre to the closest wall point
    if (walls[rec + 3] == (real)0) {
      const lane s = -v_dot(d, nrm);  // signed distance of the centre
      // behind the plane (s <= -r): ignored
      to_wall = v_sel(s > -ri, v_mul(-s, nrm), V3(2 * ri, (lane)0, (lane)0));
    } else {
      const v3 au = V3((lane)walls[rec + 8], (lane)walls[rec + 9], (lane)walls[rec + 10]);
      const v3 av = V3((lane)walls[rec + 12], (lane)walls[rec + 13], (lane)walls[rec + 14]);
      const real hu = walls[rec + 11], hv = walls[rec + 15];
      const lane u = clamp(-v_dot(d, au), -hu, hu);
      const lane v = clamp(-v_dot(d, av), -hv, hv);
      to_wall = v_add(d, v_add(v_mul(u, au), v_mul(v, av)));
    }
    const lane dist2 = v_dot(to_wall, to_wall);
    const lmask on = (dist2 < ri * ri) & (dist2 > (real)0);
    // Slots are written only where the wall is or was touched: a slot that
    // stays out of contact keeps its zeros without memory traffic.
    int on_l[LANES], keep[LANES], any_keep = 0;
    lmask_elem on_t[LANES];
#if LANES == 1
    on_t[0] = on;
#else
    LANE_STORE(on, on_t);
#endif
#pragma unroll
    for (int l = 0; l < LANES; ++l) {
      on_l[l] = on_t[l] != 0;
      keep[l] = valid[l] && (on_l[l] || ((was[l] >> w) & 1));
      now[l] |= on_l[l] << w;
      any_keep |= keep[l];
    }
    if (!any_keep) continue;
    const lane dist = SEL(on, sqrt(dist2), (real)0.5 * ri);
    const v3 nv = v_sel(on, v_mul(1 / dist, to_wall), V3((lane)1, (lane)0, (lane)0));
    const lane delta = ri - dist;
    const lane a = ri - (real)0.5 * delta;
    const v3 vw = V3((lane)wall_vel[4 * w], (lane)wall_vel[4 * w + 1], (lane)wall_vel[4 * w + 2]);
    const v3 vrel = v_sub(v_add(vi, v_cross(wi, v_mul(a, nv))), vw);
    v3 sp = gather3(wall_spring, slot);
    #pragma unroll
    for (int l = 0; l < LANES; ++l) pair[l] = (int)mat_i[l] * nmat + (int)walls[rec + 7];
    const ContactResult c = contact_law(delta, nv, vrel, wi, ri, mi, inertia,
                                        gather_pairs(pairs, pair, nmat), dt, &sp);
    scatter4(wall_spring, slot, keep, v_sel(on, sp, v_zero()), (lane)0);
    scatter4(wall_force, slot, keep, v_sel(on, v_neg(c.force), v_zero()), SEL(on, (lane)1, (lane)0));
    f = v_add(f, v_sel(on, c.force, v_zero()));
    t = v_add(t, v_sel(on, v_add(v_mul(a, c.n_cross_ft), c.rolling), v_zero()));
    e += SEL(on, c.energy, (lane)0);
    count += SEL(on, (lane)1, (lane)0);
  }
  scatter4(force, ii, valid, f, count);
  scatter4(torque, ii, valid, t, e);
#pragma unroll
  for (int l = 0; l < LANES; ++l)
    if (valid[l]) wall_touch[ii[l]] = now[l];
}

// Walls move with their prescribed velocity (compensated in float runs).
__kernel void advance_walls(__global real4* wall_point
#ifdef POS_COMPENSATED
                            , __global float4* wall_point_lo
#endif
                            , __global const real4* wall_vel, real dt, int nwalls) {
  const int w = get_global_id(0);
  if (w >= nwalls) return;
#ifdef POS_COMPENSATED
  real4 p = wall_point[w];
  float4 lo = wall_point_lo[w];
  add_compensated(&p, &lo, wall_vel[w].xyz * dt);
  wall_point[w] = p;
  wall_point_lo[w] = lo;
#else
  wall_point[w].xyz += wall_vel[w].xyz * dt;
#endif
}

#endif  // HAS_WALLS
