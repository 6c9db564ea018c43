// walls.cl — stage: wall forces (infinite planes and finite rectangles).
//
// Same contact law as between spheres, with the wall as a body of infinite
// mass and radius (R* = r_i, m* = m_i, I* = I_i). Adds to the force/torque
// written by contact_forces. Each (wall, particle) slot w*n+i keeps its
// tangential spring and the force the particle exerts ON the wall, which
// reduce_walls sums into the wall's reaction.
// Wall state: point/point_lo = current position of the wall's reference
// point (moved by advance_walls), vel = its velocity.
#ifdef HAS_WALLS

__kernel void wall_forces(__global const real4* pos POS_LO_CARG,
                          __global const real4* vel, __global const real4* omega,
                          __global const real4* walls, __global const real4* wall_point
#ifdef POS_COMPENSATED
                          , __global const float4* wall_point_lo
#endif
                          , __global const real4* wall_vel, __global real4* wall_spring,
                          __global real4* wall_force, __global const real8* pairs,
                          __global real4* force, __global real4* torque,
                          real dt, int n, int nwalls, int nmat) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const real4 pi = pos[i];
  const real4 vi = vel[i];
  const real4 wi = omega[i];
  const real ri = pi.w;
  const real mi = vi.w;
  const real ii = (real)0.4 * mi * ri * ri;
  const int row = (int)wi.w * nmat;
  real4 f = force[i];
  real4 t = torque[i];

  for (int w = 0; w < nwalls; ++w) {
    const int slot = w * n + i;
    const real4 g0 = walls[WALL_RECORD * w + 0];
    const real4 nrm = walls[WALL_RECORD * w + 1];
    // d: from the particle centre to the wall's reference point
    const real3 d = rel_pos(pi, wall_point[w] LO(i)
#ifdef POS_COMPENSATED
                            , wall_point_lo[w]
#endif
    );
    real3 to_wall;  // from the centre to the closest wall point
    if (g0.w == (real)0) {
      const real s = -dot(d, nrm.xyz);  // signed distance of the centre
      to_wall = (s > -ri) ? -s * nrm.xyz : (real3)(2 * ri);  // behind: ignore
    } else {
      const real4 au = walls[WALL_RECORD * w + 2];
      const real4 av = walls[WALL_RECORD * w + 3];
      const real u = clamp(-dot(d, au.xyz), -au.w, au.w);
      const real v = clamp(-dot(d, av.xyz), -av.w, av.w);
      to_wall = d + u * au.xyz + v * av.xyz;
    }
    const real dist2 = dot(to_wall, to_wall);
    if (dist2 >= ri * ri || dist2 == (real)0) {
      wall_spring[slot] = (real4)(0);
      wall_force[slot] = (real4)(0);
      continue;
    }
    const real dist = sqrt(dist2);
    const real3 nv = to_wall / dist;
    const real delta = ri - dist;
    const real a = ri - (real)0.5 * delta;
    const real3 vrel = vi.xyz + cross(wi.xyz, a * nv) - wall_vel[w].xyz;
    real3 sp = wall_spring[slot].xyz;
    const ContactResult c = contact_law(delta, nv, vrel, wi.xyz, a, ri, mi, ii,
                                        pairs[row + (int)nrm.w], dt, &sp);
    wall_spring[slot] = (real4)(sp, 0);
    wall_force[slot] = (real4)(-c.force, 1);
    f += (real4)(c.force, 1);
    t += (real4)(c.torque, c.energy);
  }
  force[i] = f;
  torque[i] = t;
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
