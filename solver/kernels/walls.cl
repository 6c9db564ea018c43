// walls.cl — stage: wall forces (infinite planes and finite rectangles).
//
// Same contact law as between spheres, with the wall as a body of infinite
// mass and radius (R* = r_i, m* = m_i, I* = I_i); no capillary bridges with
// walls (walls are dry). wall_contacts adds to the force/torque the pair
// stage wrote; it runs inside finish_particles (integrate.cl).
// Each particle has a wall slot for each wall near it (below), sliced like
// the neighbour lists (neighbors.cl): slot of wall w of particle i at
// WALL_SLOT (common.cl): SLOT(wall_off, i, r), r = the rank of bit w among
// the bits of wall_near[i]. A slot keeps the contact's history (HIST_PLANES records,
// plane p at p * wall_stride) and the force the particle exerts ON the
// wall, which reduce_walls sums into the wall's reaction. Particles far
// from every wall have none.
// One work item handles LANES particles (see forces.cl).
// Wall records (4 x real4 per wall, see common.cl): [0] reference point and
// shape, [1] normal and material, [2] axis_u and half_u, [3] axis_v and half_v.
// Wall state: point/point_lo = current position of the reference point
// (moved by advance_walls), vel = its velocity; point.w = the path the wall
// has travelled since the last list build.
//
// Broad phase: at every list build, build_wall_near keeps for each particle
// the walls within its radius + skin (bit w of wall_near), and wall_contacts
// tests only those. The mask stays valid while neither the particle nor the
// wall has moved skin/2 since the build (the distance to a wall changes by
// at most their two displacements): particles are watched by integrate.cl,
// walls by advance_walls, which raises the same flags (rebuild beyond
// skin/4, late beyond skin/2) and reports its speed for the host's check
// interval. A wall the host moves (a jump, not travel) has the lists and
// the masks rebuilt at the next step's start (Simulation::set_wall_point,
// request_rebuild in pipeline.h). At each build the
// slots are laid out anew (wall_widths, then grid.cl's prefix sum) and
// carry_wall_slots carries every (particle, wall) slot's history and force
// over from the previous layout (old_*).
#ifdef HAS_WALLS

// A wall's state besides its point, where the build has it: the float
// compensation of the point, and its tilt (HAS_TILT, below).
#ifdef POS_COMPENSATED
#define WALL_LO_ARG_ , __global const float* restrict wall_point_lo
#define WALL_LO_PASS_ , wall_point_lo
#else
#define WALL_LO_ARG_
#define WALL_LO_PASS_
#endif
#ifdef HAS_TILT
#define WALL_TURN_ARG_ , __global const real* restrict wall_turn
#define WALL_TURN_PASS_ , wall_turn
#else
#define WALL_TURN_ARG_
#define WALL_TURN_PASS_
#endif
#define WALL_STATE_ARG WALL_LO_ARG_ WALL_TURN_ARG_
#define WALL_STATE_PASS WALL_LO_PASS_ WALL_TURN_PASS_

// Tilting walls (a shear box's loading cap free to tilt, HAS_TILT): a
// rectangle may turn about its axis_v through its reference point.
// wall_turn, a real4 per wall: (tilt t in rad, its rate in rad/s, 1/J or 0,
// the beads' moment about axis_v last step in N m); 1/J > 0 lets the wall
// turn (the host sets it while the wall is a dead weight, J = M (2 half_u)^2
// / 12), 0 holds it at its tilt. The record's normal and axis_u are those
// at t = 0, turned by tilt_axes (common.cl).

// Vector from each lane's centre to the closest point of wall w; returns its
// squared length (>= r^2 or 0: no contact). to_ref: from the centre to the
// wall's reference point.
INLINE lane wall_gap(__global const real* walls, __global const real* wall_point WALL_STATE_ARG,
                     int w, LanePos pi, lane ri, v3* to_wall, v3* to_ref) {
  const int rec = 4 * WALL_RECORD * w;  // reals
  LanePos wp;
  wp.hi = V3((lane)wall_point[4 * w], (lane)wall_point[4 * w + 1], (lane)wall_point[4 * w + 2]);
#ifdef POS_COMPENSATED
  wp.lo = V3((lane)wall_point_lo[4 * w], (lane)wall_point_lo[4 * w + 1],
             (lane)wall_point_lo[4 * w + 2]);
#else
  wp.lo = v_zero();
#endif
  const v3 d = separation(pi, wp);  // centre -> wall reference point
  *to_ref = d;
  real3 n = (real3)(walls[rec + 4], walls[rec + 5], walls[rec + 6]);
  real3 axis_u = (real3)(walls[rec + 8], walls[rec + 9], walls[rec + 10]);
  const real3 axis_v = (real3)(walls[rec + 12], walls[rec + 13], walls[rec + 14]);
#ifdef HAS_TILT
  tilt_axes(wall_turn[4 * w], axis_v, &n, &axis_u);
#endif
  const v3 nrm = V3((lane)n.x, (lane)n.y, (lane)n.z);
  if (walls[rec + 3] == (real)0) {
    const lane s = -v_dot(d, nrm);  // signed distance of the centre; behind the plane: ignored
    *to_wall = v_sel(s > -ri, v_mul(-s, nrm), V3(2 * ri, (lane)0, (lane)0));
  } else {
    const v3 au = V3((lane)axis_u.x, (lane)axis_u.y, (lane)axis_u.z);
    const v3 av = V3((lane)axis_v.x, (lane)axis_v.y, (lane)axis_v.z);
    const real hu = walls[rec + 11], hv = walls[rec + 15];
    const lane u = clamp(-v_dot(d, au), -hu, hu);
    const lane v = clamp(-v_dot(d, av), -hv, hv);
    *to_wall = v_add(d, v_add(v_mul(u, au), v_mul(v, av)));
  }
  return v_dot(*to_wall, *to_wall);
}

INLINE void lane_flags(lmask m, int* out) {
  lmask_elem t[LANES];
#if LANES == 1
  t[0] = m;
#else
  LANE_STORE(m, t);
#endif
#pragma unroll
  for (int l = 0; l < LANES; ++l) out[l] = t[l] != 0;
}

// Bit w of wall_near[i]: wall w lies within r_i + skin of particle i (a
// plane: the centre's signed distance within +-(r_i + skin); a rectangle: the
// distance to its closest point below r_i + skin). The float compensation
// terms (below 1 ulp of a coordinate) are far below the skin and ignored.
__kernel void build_wall_near(__global const real4* restrict pos,
                              __global const real4* restrict walls,
                              __global const real4* restrict wall_point,
                              __global const real4* restrict wall_turn,
                              __global const real4* restrict membrane,
                              __global int* restrict wall_near, real skin, int n, int nwalls) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const real4 pi = pos[i];
  const real reach = pi.w + skin;
  int mask = 0;
  for (int w = 0; w < nwalls; ++w) {
    const real3 d = wall_point[w].xyz - pi.xyz;  // centre -> wall reference point
    const real4 shape = walls[WALL_RECORD * w];
    real3 nrm = walls[WALL_RECORD * w + 1].xyz;
    const real4 av = walls[WALL_RECORD * w + 3];
    real4 au = walls[WALL_RECORD * w + 2];
#ifdef HAS_TILT
    real3 axis = au.xyz;
    tilt_axes(wall_turn[w].x, av.xyz, &nrm, &axis);
    au.xyz = axis;
#endif
    real dist;
    if (shape.w == (real)0) {
      dist = fabs(dot(d, nrm));
    } else {
      const real u = clamp(-dot(d, au.xyz), -au.w, au.w);
      const real v = clamp(-dot(d, av.xyz), -av.w, av.w);
      dist = length(d + u * au.xyz + v * av.xyz);
    }
    if (dist < reach) mask |= 1 << w;
  }
#ifdef HAS_MEMBRANE
  // A membrane's last row is sealed to its platen (membrane.cl): part of the
  // cap, not beads pressing on it. The row's height follows the platen one
  // step late (the servo moves the platen after the beads), so a contact
  // between them would feed the servo's own last step back to it: at a
  // tangent contact in float the platen chattered at its speed cap.
  const real4 m2 = membrane[2];
  const int k = i - (int)m2.x, rows = (int)m2.y, cols = (int)m2.z, platen = (int)m2.w;
  if (platen >= 0 && k >= (rows - 1) * cols && k < rows * cols) mask &= ~(1 << platen);
#endif
  wall_near[i] = mask;
}

// Slice g's wall block size in slots (its particles' most near walls,
// times SLICE); entry `slices` is 0, so the prefix sum ends with the total.
__kernel void wall_widths(__global const int* restrict wall_near, __global uint* restrict width,
                          int n, int slices) {
  const int g = get_global_id(0);
  if (g > slices) return;
  int most = 0;
  for (int i = g * SLICE; g < slices && i < min(n, (g + 1) * SLICE); ++i)
    most = max(most, (int)popcount(wall_near[i]));
  width[g] = (uint)(most * SLICE);
}

// The new layout's slots from the previous one: a wall near the particle
// then and now keeps its history and force; a newly near wall starts at 0.
__kernel void carry_wall_slots(__global const int* restrict old_near,
                               __global const uint* restrict old_off,
                               __global const real4* restrict old_spring,
                               __global const real4* restrict old_force, int old_stride,
                               __global const int* restrict wall_near,
                               __global const uint* restrict wall_off,
                               __global real4* restrict wall_spring,
                               __global real4* restrict wall_force, int stride, int n,
                               int nwalls) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const int was = old_near[i], mask = wall_near[i];
  for (int w = 0; w < nwalls; ++w) {
    if (!((mask >> w) & 1)) continue;
    const int to = WALL_SLOT(wall_off, i, mask, w);
    const int kept = (was >> w) & 1;
    const int from = kept ? WALL_SLOT(old_off, i, was, w) : 0;
    for (int p = 0; p < HIST_PLANES; ++p)
      wall_spring[(size_t)p * stride + to] =
          kept ? old_spring[(size_t)p * old_stride + from] : (real4)(0);
    wall_force[to] = kept ? old_force[from] : (real4)(0);
  }
}

// The walls' travel restarts with the lists (point.w, see above).
__kernel void reset_wall_travel(__global real4* wall_point, int nwalls) {
  const int w = get_global_id(0);
  if (w < nwalls) wall_point[w].w = 0;
}

// The work item's particles, one per lane (past n, lanes stand in with the
// last particle and have no walls), their near walls (mask, bit w) and the
// walls they touched last step (was); returns the walls near any lane.
INLINE int wall_lanes(int base, int n, __global const int* restrict wall_near,
                      __global const int* restrict wall_touch, int* ii, int* valid, int* mask,
                      int* was, int* now) {
  int near = 0;  // walls near any lane (broad phase)
#pragma unroll
  for (int l = 0; l < LANES; ++l) {
    valid[l] = base + l < n;
    ii[l] = valid[l] ? base + l : n - 1;
    mask[l] = valid[l] ? wall_near[ii[l]] : 0;  // a wall touched is near: was, now within mask
    was[l] = valid[l] ? wall_touch[ii[l]] & mask[l] : 0;  // walls touched last step (bit w)
    near |= mask[l];
    now[l] = 0;
  }
  return near;
}

// Geometry of the near walls first: bit w of now[l] where lane l's
// particle touches wall w. Returns whether any lane touches a wall now or
// did last step.
INLINE int touched_walls(__global const real* restrict walls,
                         __global const real* restrict wall_point WALL_STATE_ARG, int near,
                         int nwalls, const Owner* o, const int* valid, const int* mask,
                         const int* was, int* now) {
  int busy = 0;
  for (int w = 0; w < nwalls; ++w) {
    if (!((near >> w) & 1)) continue;
    v3 to_wall, to_ref;
    const lane dist2 =
        wall_gap(walls, wall_point WALL_STATE_PASS, w, o->p, o->r, &to_wall, &to_ref);
    int on[LANES];
    lane_flags((dist2 < o->r * o->r) & (dist2 > (real)0), on);
#pragma unroll
    for (int l = 0; l < LANES; ++l) now[l] |= (on[l] << w) & mask[l];
  }
#pragma unroll
  for (int l = 0; l < LANES; ++l) busy |= valid[l] && (now[l] | was[l]);
  return busy;
}

// The lanes' slots of wall w where it is touched now or was last step
// (keep); returns whether any lane keeps one. Slots are written only there:
// a slot that stays out of contact keeps its zeros without memory traffic.
INLINE int kept_wall_slots(int w, const int* ii, const int* valid, const int* mask,
                           const int* now, const int* was, __global const uint* restrict wall_off,
                           int* keep, int* slot) {
  int any_keep = 0;
#pragma unroll
  for (int l = 0; l < LANES; ++l) {
    keep[l] = valid[l] && (((now[l] | was[l]) >> w) & 1);
    any_keep |= keep[l];
    slot[l] = keep[l] ? WALL_SLOT(wall_off, ii[l], mask[l], w) : 0;
  }
  return any_keep;
}

// The contact with wall w: whether it touches (`on`), the normal towards the
// wall, overlap and lever arm, and (tilting walls) the contact point from
// the wall's reference point; lanes that do not touch get a stand-in (half
// the radius along x).
typedef struct {
  lmask on;
  v3 nv;
  lane delta, a;
#ifdef HAS_TILT
  v3 arm;
#endif
} WallContact;

INLINE WallContact wall_contact(__global const real* restrict walls,
                                __global const real* restrict wall_point WALL_STATE_ARG, int w,
                                const Owner* o) {
  v3 to_wall, to_ref;
  const lane dist2 = wall_gap(walls, wall_point WALL_STATE_PASS, w, o->p, o->r, &to_wall, &to_ref);
  WallContact k;
#ifdef HAS_TILT
  k.arm = v_sub(to_wall, to_ref);
#endif
  k.on = (dist2 < o->r * o->r) & (dist2 > (real)0);
  const lane dist = SEL(k.on, sqrt(dist2), (real)0.5 * o->r);
  k.nv = v_sel(k.on, v_mul(1 / dist, to_wall), V3((lane)1, (lane)0, (lane)0));
  k.delta = fmax(o->r - dist, (real)0);  // >= 0 whatever the rounding (forces.cl)
  k.a = o->r - (real)0.5 * k.delta;
  return k;
}

// The history of the (particle, wall) slots, as in forces.cl (plane p at
// p * wall_stride records).
INLINE History load_wall_history(__global const real* restrict wall_spring, int wall_stride,
                                 const int* slot) {
  Lane4 rec[HIST_RECORDS];
  for (int p = 0; p < HIST_PLANES; ++p)
    rec[p] = gather4(wall_spring + 4 * (size_t)p * (size_t)wall_stride, slot);
  return history_from_planes(rec);
}

INLINE void store_wall_history(__global real* restrict wall_spring, int wall_stride,
                               const int* slot, const int* keep, lmask on, History h) {
  Lane4 rec[HIST_RECORDS];
  history_planes_of(h, on, rec);
  for (int p = 0; p < HIST_PLANES; ++p)
    scatter4(wall_spring + 4 * (size_t)p * (size_t)wall_stride, slot, keep, rec[p].xyz, rec[p].w);
}

// The law between each lane's particle and wall w moving at vw (R* = r_i,
// m* = the mass of i's body, forces.cl body_mass; roll_inertia the I* of
// the rolling cap).
INLINE ContactResult wall_law(const Owner* o, WallContact k, v3 vw, lane roll_inertia, int w,
                              __global const real* restrict walls,
                              __global const real* restrict pairs, int nmat, real dt,
                              real rolling_damping, History* h) {
  int pair[LANES];
  const v3 vrel = v_sub(v_add(o->v, v_cross(o->w, v_mul(k.a, k.nv))), vw);
  const int wall_mat = (int)walls[4 * WALL_RECORD * w + 7];
#pragma unroll
  for (int l = 0; l < LANES; ++l) pair[l] = (int)o->row[l] * nmat + wall_mat;
  // The normal dashpot's record (contact_law.cl) extrapolates what the rest
  // of the world did to the approach speed. A wall is no body pushed by
  // forces: it keeps its velocity, and a servo's step-to-step changes are
  // not to be extrapolated. So the record is kept in the particle's frame,
  // shifted by the wall's normal momentum m_i v_w.n around the call (0
  // stays "none").
  const lane wall_vn = o->m * v_dot(vw, k.nv);
  h->dash = SEL(h->dash != (real)0, h->dash - wall_vn, (lane)0);
  const ContactResult c = contact_law_h(k.delta, k.nv, vrel, o->w, o->r, o->m, roll_inertia,
                                        gather_pairs(pairs, pair, nmat), dt, h, rolling_damping);
  h->dash += wall_vn;
  return c;
}

// The contact's force on the wall (and a contact flag) into the slots kept;
// the particle's force, torque, energy and contact count into its sums.
INLINE void add_wall_contact(__global real* restrict wall_force, const int* slot,
                             const int* keep, WallContact k, ContactResult c, ContactSums* sum) {
  scatter4(wall_force, slot, keep, v_sel(k.on, v_neg(c.force), v_zero()),
           SEL(k.on, (lane)1, (lane)0));
  sum->f = v_add(sum->f, v_sel(k.on, c.force, v_zero()));
  sum->t = v_add(sum->t, v_sel(k.on, v_add(v_mul(k.a, c.n_cross_ft), c.rolling), v_zero()));
  sum->e += SEL(k.on, c.energy, (lane)0);
  sum->touching += SEL(k.on, (lane)1, (lane)0);
}

// The wall contacts of the LANES particles from `base` on.
INLINE void wall_contacts(int base, __global const real* restrict pos POS_LO_SARG_FN,
                          __global const real* restrict vel, __global const real* restrict omega,
                          __global const real* restrict walls,
                          __global const real* restrict wall_point WALL_STATE_ARG,
                          __global const real* restrict wall_vel,
                          __global const uint* restrict wall_off,
                          __global real* restrict wall_spring, __global real* restrict wall_force,
                          int wall_stride, __global const real* restrict pairs,
                          __global real* restrict force, __global real* restrict torque,
                          __global int* restrict wall_touch,
                          __global const int* restrict wall_near,
                          __global const real* restrict body_offset,
                          __global const int* restrict contacts_last, real dt,
                          real rolling_damping, int n, int nwalls, int nmat) {
  int ii[LANES], valid[LANES], was[LANES], now[LANES], mask[LANES];
  const int near = wall_lanes(base, n, wall_near, wall_touch, ii, valid, mask, was, now);
  // Most particles are near no wall and leave at once.
  if (!near) return;
  Owner own;
  own.p = gather_pos(pos POS_LO_PASS, ii);
  own.r = gather(pos, ii, 3);
  if (!touched_walls(walls, wall_point WALL_STATE_PASS, near, nwalls, &own, valid, mask, was, now))
    return;

  gather_motion(&own, vel, omega, body_offset, contacts_last, ii);
  const Lane4 f0 = gather4(force, ii), t0 = gather4(torque, ii);
  ContactSums sum;  // the pair stage's, which the walls add to
  sum.f = f0.xyz;
  sum.t = t0.xyz;
  sum.touching = f0.w;
  sum.e = t0.w;
#ifdef HAS_SHARED_ROLLING_CAP
  // the constant rolling torque's cap is shared among the contacts (forces.cl)
  const lane roll_inertia = own.inertia / own.cap;
#else
  const lane roll_inertia = own.inertia;
#endif

  for (int w = 0; w < nwalls; ++w) {
    int keep[LANES], slot[LANES];
    if (!kept_wall_slots(w, ii, valid, mask, now, was, wall_off, keep, slot)) continue;
    const WallContact k = wall_contact(walls, wall_point WALL_STATE_PASS, w, &own);
    v3 vw = V3((lane)wall_vel[4 * w], (lane)wall_vel[4 * w + 1], (lane)wall_vel[4 * w + 2]);
#ifdef HAS_TILT
    const real spin = wall_turn[4 * w + 1];  // the wall's surface moves at v + spin av x arm
    if (spin != (real)0) {
      const int rec = 4 * WALL_RECORD * w;
      const v3 av = V3((lane)walls[rec + 12], (lane)walls[rec + 13], (lane)walls[rec + 14]);
      vw = v_add(vw, v_mul((lane)spin, v_cross(av, k.arm)));
    }
#endif
    History h = load_wall_history(wall_spring, wall_stride, slot);
    const ContactResult c = wall_law(&own, k, vw, roll_inertia, w, walls, pairs, nmat, dt,
                                     rolling_damping, &h);
    store_wall_history(wall_spring, wall_stride, slot, keep, k.on, h);
    add_wall_contact(wall_force, slot, keep, k, c, &sum);
  }
  scatter4(force, ii, valid, sum.f, sum.touching);
  scatter4(torque, ii, valid, sum.t, sum.e);
#pragma unroll
  for (int l = 0; l < LANES; ++l)
    if (valid[l]) wall_touch[ii[l]] = now[l];
}

// Wall w moves with its velocity (compensated in float runs), keeps its
// travel since the last list build in point.w and raises the list flags as
// integrate.cl does for particles (the broad phase above). wall_point_lo is
// unused in double runs.
INLINE void advance_wall(int w, __global real4* wall_point, __global float4* wall_point_lo,
                         __global const real4* wall_vel, __global volatile int* flags, real dt,
                         real skin) {
  const real3 v = wall_vel[w].xyz;
  real4 p = wall_point[w];
#ifdef POS_COMPENSATED
  float4 lo = wall_point_lo[w];
  add_compensated(&p, &lo, v * dt);
  wall_point_lo[w] = lo;
#else
  p.xyz += v * dt;
#endif
  p.w += length(v) * dt;
  wall_point[w] = p;
  if (p.w > (real)0.25 * skin) flags[FLAG_REBUILD] = 1;
  if (p.w > (real)0.5 * skin) flags[FLAG_LATE] = 1;
  const int v2 = as_int((float)dot(v, v));
  if (v2 > flags[FLAG_MAX_SPEED2]) atomic_max(&flags[FLAG_MAX_SPEED2], v2);
}

#ifdef HAS_TILT
// The moment about axis_v through wall w's reference point of the force f
// a particle at x exerts on the wall. The contact point is the plate's
// point closest to x (wall_gap): x's offset projected onto the plane and
// clamped to the rectangle, so a force along the plane has no moment about
// an axis in it, and a bead past an edge pushes at the edge.
INLINE real wall_moment(int w, real3 x, real3 f, __global const real4* walls,
                        __global const real4* wall_point, __global const real4* wall_turn) {
  real3 n = walls[WALL_RECORD * w + 1].xyz, au = walls[WALL_RECORD * w + 2].xyz;
  const real4 av = walls[WALL_RECORD * w + 3];
  tilt_axes(wall_turn[w].x, av.xyz, &n, &au);
  const real3 d = x - wall_point[w].xyz;
  const real u = clamp(dot(d, au), -walls[WALL_RECORD * w + 2].w, walls[WALL_RECORD * w + 2].w);
  const real v = clamp(dot(d, av.xyz), -av.w, av.w);
  return dot(cross(u * au + v * av.xyz, f), av.xyz);
}
#endif

// The forces of chunk c's particles (`chunk` consecutive indices) on each
// wall, summed in index order in one pass over the chunk (a particle's wall
// slots come in the order of its near walls' bits): partial[w * chunks + c].
// With tilting walls, also the moments on the walls free to turn:
// partial[(nwalls + w) * chunks + c].x (x = pos, the particles' new
// positions: their offsets along the wall differ from the step's by v dt).
INLINE void wall_chunk_sums(int c, __global const int* wall_near, __global const uint* wall_off,
                            __global const real4* wall_force, __global real4* partial,
                            __global const real4* pos, __global const real4* walls,
                            __global const real4* wall_point, __global const real4* wall_turn,
                            int n, int chunk, int chunks, int nwalls) {
  real4 sum[32];  // a wall mask has 32 bits
  for (int w = 0; w < nwalls; ++w) sum[w] = (real4)(0);
#ifdef HAS_TILT
  real moment[32];
  for (int w = 0; w < nwalls; ++w) moment[w] = 0;
#endif
  const int lo = c * chunk, hi = min(n, lo + chunk);
  for (int i = lo; i < hi; ++i) {
    int r = 0;  // rank of wall w among the near walls: its slot (WALL_SLOT)
    for (uint m = (uint)wall_near[i]; m != 0; m &= m - 1, ++r) {
      const int w = popcount((m & (0u - m)) - 1);  // lowest bit's wall
      const real4 f = wall_force[SLOT(wall_off, i, r)];
      sum[w] += f;
#ifdef HAS_TILT
      if (f.w != (real)0 && wall_turn[w].z > (real)0)
        moment[w] += wall_moment(w, pos[i].xyz, f.xyz, walls, wall_point, wall_turn);
#endif
    }
  }
  for (int w = 0; w < nwalls; ++w) partial[w * chunks + c] = sum[w];
#ifdef HAS_TILT
  for (int w = 0; w < nwalls; ++w) partial[(nwalls + w) * chunks + c] = (real4)(moment[w], 0, 0, 0);
#endif
}

// All walls, one work item each (scenes without servo walls; servo_walls
// below advances the walls itself).
__kernel void advance_walls(__global real4* wall_point, __global float4* wall_point_lo,
                            __global const real4* wall_vel, __global volatile int* flags, real dt,
                            real skin, int nwalls) {
  const int w = get_global_id(0);
  if (w < nwalls) advance_wall(w, wall_point, wall_point_lo, wall_vel, flags, dt, skin);
}

#endif  // HAS_WALLS (servo_walls below needs it too)

#ifdef HAS_SERVO
// Force-controlled walls (one work item): sums the group partials of
// reduce_walls into each wall's force, adds it to the wall's running sum
// (mean: sum, steps in w) for the host's averaged readings, and moves a
// controlled wall along its normal n from its reaction F = -(force on wall) . n
// in one of two ways:
//   servo        a PI law on the error e = target - F:
//                  v = clamp(gain e + v_i, +-max_speed),  v_i += gain e dt / T_i,
//                where v_i (clamped to +-max_speed) integrates only while the
//                proportional part alone is below the cap (no wind-up);
//   dead weight  a rigid body of mass M pushed along n by the constant force
//                `target` (a hanger's weight) and back by the particles:
//                  M du/dt = target - F,  u += dt (target - F) / M,
//                the same symplectic Euler step as the particles' (integrate.cl).
// A rigid group (a shear box's floating upper half): member walls name a
// leader; the leader's controller takes the members' forces along its own
// normal too, and every member moves at the leader's velocity.
// A stop bounds a dead weight's travel along its normal from where the
// scene put it (the upper half coming to rest on the lower one): the wall
// halts there and its momentum is lost (a plastic impact).
// servo: 2 real4 per wall, (target, gain, max_speed, on) and
// (1/T_i, 1/M, leader + 1 or 0, stop or 0);
// 1/M > 0 selects the dead weight (gain, max_speed, T_i unused).
// reading: 1 real4 per wall, (F this step, sum of F since the host last
// reset it, v_i or u, steps in the sum).
INLINE real4 wall_sum(int w, __global const real4* partial, int groups) {
  real4 sum = (real4)(0);
  for (int g = 0; g < groups; ++g) sum += partial[w * groups + g];
  return sum;
}

// The reaction along n of wall w and of the walls that follow it.
INLINE real group_reaction(int w, real3 n, real3 own, __global const real4* servo,
                           __global const real4* partial, int groups, int nwalls) {
  real3 f = own;
  for (int m = 0; m < nwalls; ++m)
    if ((int)servo[2 * m + 1].z == w + 1) f += wall_sum(m, partial, groups).xyz;
  return -dot(f, n);
}

// The largest speed along n that keeps wall w short of its stop.
INLINE real stop_speed(int w, real3 n, real stop, __global const real4* walls,
                       __global const real4* wall_point, real dt) {
  const real travel = dot(wall_point[w].xyz - walls[WALL_RECORD * w].xyz, n);
  return stop > (real)0 ? fmax(stop - travel, (real)0) / dt : (real)INFINITY;
}

INLINE void servo_wall(int w, __global const real4* walls, __global const real4* servo,
                       __global const real4* partial, __global real4* wall_vel,
                       __global real4* reading, __global real4* mean,
                       __global const real4* wall_point, real dt, int groups, int nwalls) {
  const real4 sum = wall_sum(w, partial, groups);
  mean[w] += (real4)(sum.xyz, 1);
  const real4 c = servo[2 * w];
  if (c.w == (real)0) return;
  const real inv_ti = servo[2 * w + 1].x;
  const real inv_mass = servo[2 * w + 1].y;
  const real3 n = walls[WALL_RECORD * w + 1].xyz;
  const real f = group_reaction(w, n, sum.xyz, servo, partial, groups, nwalls);
  real4 r = reading[w];
  const real e = c.x - f;
  real v;
  if (inv_mass > (real)0) {
    v = dot(wall_vel[w].xyz, n) + dt * e * inv_mass;
    v = fmin(v, stop_speed(w, n, servo[2 * w + 1].w, walls, wall_point, dt));
    r.z = v;
  } else {
    const real vp = c.y * e;
    real vi = r.z;
    if (fabs(vp) < c.z) vi = clamp(vi + vp * dt * inv_ti, -c.z, c.z);
    v = clamp(vp + vi, -c.z, c.z);
    r.z = vi;
  }
  reading[w] = (real4)(f, r.y + f, r.z, r.w + 1);
  wall_vel[w] = (real4)(v * n, 0);
}

#ifdef HAS_TILT
// A wall free to turn (wall_turn[w].z = 1/J > 0) as a rigid body about its
// axis_v: J dspin/dt = moment, the same symplectic Euler step as the
// particles'. Turning about axis_v moves the plate's points along its normal
// by up to spin dt half_u: that travel counts towards the list flags with
// its point's (advance_wall, next), and the edge's speed with the point's
// towards the host's check interval.
INLINE void turn_wall(int w, __global const real4* walls, __global const real4* partial,
                      __global real4* wall_turn, __global real4* wall_point,
                      __global const real4* wall_vel, __global volatile int* flags, real dt,
                      int groups, int nwalls) {
  real4 t = wall_turn[w];
  if (t.z == (real)0) return;
  real moment = 0;
  for (int g = 0; g < groups; ++g) moment += partial[(nwalls + w) * groups + g].x;
  t.y += dt * moment * t.z;
  t.x += dt * t.y;
  t.w = moment;
  wall_turn[w] = t;
  const real edge = fabs(t.y) * walls[WALL_RECORD * w + 2].w;  // half_u's speed
  wall_point[w].w += edge * dt;
  const real speed = length(wall_vel[w].xyz) + edge;
  const int v2 = as_int((float)(speed * speed));
  if (v2 > flags[FLAG_MAX_SPEED2]) atomic_max(&flags[FLAG_MAX_SPEED2], v2);
}
#endif

// The walls' whole step, by one work item: the forces on them (with
// `reduce` set, the chunk sums of reduce_walls, computed here; else
// reduce_walls ran before), every wall's servo step, then every wall
// (a group's members at their leader's velocity)
// advances (advance_wall), controlled or not. CPUs run it at the end of
// finish_particles (integrate.cl; one pass over the masks costs less than
// a launch), GPUs as servo_walls after reduce_walls, in parallel.

INLINE void walls_step(__global const real4* walls, __global const real4* servo,
                       __global const int* wall_near, __global const uint* wall_off,
                       __global const real4* wall_force, __global real4* partial,
                       __global real4* wall_vel, __global real4* reading, __global real4* mean,
                       __global real4* wall_point, __global float4* wall_point_lo,
                       __global real4* wall_turn, __global const real4* pos,
                       __global volatile int* flags, real dt, real skin, int n, int chunk,
                       int groups, int reduce, int nwalls) {
  for (int c = 0; reduce && c < groups; ++c)
    wall_chunk_sums(c, wall_near, wall_off, wall_force, partial, pos, walls, wall_point,
                    wall_turn, n, chunk, groups, nwalls);
  for (int w = 0; w < nwalls; ++w)
    servo_wall(w, walls, servo, partial, wall_vel, reading, mean, wall_point, dt, groups, nwalls);
#ifdef HAS_TILT
  for (int w = 0; w < nwalls; ++w)
    turn_wall(w, walls, partial, wall_turn, wall_point, wall_vel, flags, dt, groups, nwalls);
#endif
  for (int w = 0; w < nwalls; ++w) {
    const int leader = (int)servo[2 * w + 1].z - 1;
    if (leader >= 0) wall_vel[w] = wall_vel[leader];
    advance_wall(w, wall_point, wall_point_lo, wall_vel, flags, dt, skin);
  }
}

// walls_step as a launch of one work item (GPUs, after reduce_walls).
__kernel void servo_walls(__global const real4* walls, __global const real4* servo,
                          __global real4* partial, __global real4* wall_vel,
                          __global real4* reading, __global real4* mean,
                          __global real4* wall_point, __global float4* wall_point_lo,
                          __global real4* wall_turn, __global volatile int* flags, real dt,
                          real skin, int groups, int nwalls) {
  if (get_global_id(0) != 0) return;
  walls_step(walls, servo, 0, 0, 0, partial, wall_vel, reading, mean, wall_point, wall_point_lo,
             wall_turn, 0, flags, dt, skin, 0, 0, groups, 0, nwalls);
}
#endif  // HAS_SERVO
