// walls.cl — stage: wall forces (infinite planes and finite rectangles).
//
// Same contact law as between spheres, with the wall as a body of infinite
// mass and radius (R* = r_i, m* = m_i, I* = I_i). Adds to the force/torque
// written by contact_forces. Each (wall, particle) slot w*n+i keeps its
// tangential spring and the force the particle exerts ON the wall, which
// reduce_walls sums into the wall's reaction.
// Wall records (4 x real4 per wall, see common.cl): [0] reference point and
// shape, [1] normal and material, [2] axis_u and half_u, [3] axis_v and half_v.
// Wall state: point/point_lo = current position of the reference point
// (moved by advance_walls), vel = its velocity.
#ifdef HAS_WALLS

__kernel void wall_forces(__global const real* pos POS_LO_SARG,
                          __global const real* vel, __global const real* omega,
                          __global const real* walls, __global const real* wall_point
#ifdef POS_COMPENSATED
                          , __global const float* wall_point_lo
#endif
                          , __global const real* wall_vel, __global real* wall_spring,
                          __global real* wall_force, __global const real* pairs,
                          __global real* force, __global real* torque,
                          real dt, int n, int nwalls, int nmat) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const v3 xi = load3(pos, i);
  const real ri = load_w(pos, i);
  const v3 vi = load3(vel, i);
  const real mi = load_w(vel, i);
  const v3 wi = load3(omega, i);
  const real ii = (real)0.4 * mi * ri * ri;
  const int row = (int)load_w(omega, i) * nmat;
  v3 f = load3(force, i);
  real count = load_w(force, i);
  v3 t = load3(torque, i);
  real e = load_w(torque, i);

  for (int w = 0; w < nwalls; ++w) {
    const int slot = w * n + i;
    const int rec = WALL_RECORD * w;
    // d: from the particle centre to the wall's reference point
    v3 d = v_sub(load3(wall_point, w), xi);
#ifdef POS_COMPENSATED
    d = v_add(d, V3(wall_point_lo[4 * w] - pos_lo[4 * i], wall_point_lo[4 * w + 1] - pos_lo[4 * i + 1],
                    wall_point_lo[4 * w + 2] - pos_lo[4 * i + 2]));
#endif
    const v3 nrm = load3(walls, rec + 1);
    v3 to_wall;  // from the centre to the closest wall point
    if (load_w(walls, rec) == (real)0) {
      const real s = -v_dot(d, nrm);  // signed distance of the centre
      to_wall = (s > -ri) ? v_mul(-s, nrm) : V3(2 * ri, 0, 0);  // behind the plane: ignored
    } else {
      const v3 au = load3(walls, rec + 2);
      const v3 av = load3(walls, rec + 3);
      const real hu = load_w(walls, rec + 2), hv = load_w(walls, rec + 3);
      const real u = clamp(-v_dot(d, au), -hu, hu);
      const real v = clamp(-v_dot(d, av), -hv, hv);
      to_wall = v_add(d, v_add(v_mul(u, au), v_mul(v, av)));
    }
    const real dist2 = v_dot(to_wall, to_wall);
    if (dist2 >= ri * ri || dist2 == (real)0) {
      store4(wall_spring, slot, v_zero(), 0);
      store4(wall_force, slot, v_zero(), 0);
      continue;
    }
    const real dist = sqrt(dist2);
    const v3 nv = v_mul(1 / dist, to_wall);
    const real delta = ri - dist;
    const real a = ri - (real)0.5 * delta;
    const v3 vrel = v_sub(v_add(vi, v_cross(wi, v_mul(a, nv))), load3(wall_vel, w));
    v3 sp = load3(wall_spring, slot);
    const ContactResult c = contact_law(delta, nv, vrel, wi, a, ri, mi, ii, pairs,
                                        row + (int)load_w(walls, rec + 1), dt, &sp);
    store4(wall_spring, slot, sp, 0);
    store4(wall_force, slot, v_neg(c.force), 1);
    f = v_add(f, c.force);
    t = v_add(t, c.torque);
    e += c.energy;
    count += 1;
  }
  store4(force, i, f, count);
  store4(torque, i, t, e);
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
