// render_pack.cl — the renderer's data path: particle and contact records
// packed into compact float buffers on the device (view_pack.h).
//
// A program of its own, built with common.cl in front and the solver's
// options (precision, HAS_WALLS, SLICE; LANES is irrelevant, the
// code is scalar, one particle per work item), so a run that never draws
// never compiles it. The output buffers may be plain OpenCL buffers or
// buffers shared with OpenGL; the kernels only write them.
//
// Outputs are float whatever the precision: positions relative to a view
// origin near the specimen, field values in SI units. In float runs the
// compensated positions (hi + lo, see common.cl) are reduced to one float
// only after the origin is taken off, as (hi - origin) + (lo - origin_lo),
// so a bead keeps float's relative precision over the specimen's size.
//
// Min/max and the contact statistics leave one partial per work group,
// reduced in a fixed order; the host combines the partials (deterministic).
// Segments are compacted with an atomic counter: their order may vary from
// run to run, their set and the statistics do not.

// ColorField in view_pack.h, same order.
#define FIELD_SIZE 0
#define FIELD_LAYER 1
#define FIELD_SPEED 2
#define FIELD_DISPLACEMENT 3
#define FIELD_CONTACTS 4
#define FIELD_ROTATION 5
#define FIELD_GRAIN 6
#define FIELD_NONAFFINE 7

// Compensation term of record i (a float4 buffer in float runs; double runs
// have none and pass a placeholder that is never read).
#ifdef POS_COMPENSATED
#define LO_AT(p, i) ((p)[i])
#else
#define LO_AT(p, i) ((real4)(0))
#endif

// b - a for two compensated positions (hi + lo), formed as in
// common.cl's rel_pos: (b_hi - a_hi) + (b_lo - a_lo).
INLINE real3 diff_pos(real4 b, real4 b_lo, real4 a, real4 a_lo) {
  real3 d = b.xyz - a.xyz;
#ifdef POS_COMPENSATED
  d += b_lo.xyz - a_lo.xyz;
#endif
  return d;
}

// Work-group reduction in a fixed order (pairwise, stride doubling), for any
// work-group size: `rows` rows of `size` values each sit in `s`, row r is
// folded with COMBINE(a, b, r) (a = a op b) and its result left in s[r * size].
#define GROUP_REDUCE(s, size, l, rows, COMBINE)                              \
  for (int stride = 1; stride < (size); stride <<= 1) {                     \
    if (((l) & (2 * stride - 1)) == 0 && (l) + stride < (size))              \
      for (int r = 0; r < (rows); ++r) {                                     \
        const int at = r * (size) + (l);                                     \
        COMBINE(s[at], s[at + stride], r);                                   \
      }                                                                      \
    barrier(CLK_LOCAL_MEM_FENCE);                                            \
  }

// Row 0 min, row 1 max.
#define MINMAX_COMBINE(a, b, r) a = (r) == 0 ? fmin(a, b) : fmax(a, b)

// Per bead: beads[i] = (x - origin, radius) and values[i] = the field.
// partial[2g], partial[2g+1]: min and max of the field over group g.
// ref/ref_lo: the reference positions (Displacement, Layer), relative to the
// model origin like pos. z0/z0_lo: the lowest band centre, relative to the
// model origin; band: the band height. body: each particle's clump, -1 for
// a free sphere (Model::body_buffer; a one-entry stand-in, never read,
// without HAS_CLUMPS); clumps: their number. Grain: c for the members of
// clump c, clumps + i for a free sphere i. affine_a0..a2 (rows of A),
// affine_centre (relative to the model origin) and affine_mean: the affine
// displacement field NonAffine takes off (ViewPacker's affine_fit).
__kernel void pack_beads(__global const real4* pos, __global const real4* pos_lo,
                         __global const real4* vel, __global const real4* omega,
                         __global const real4* force, __global const real4* ref,
                         __global const real4* ref_lo, __global const int* body, int clumps,
                         real4 origin, real4 origin_lo,
                         int field, real z0, real z0_lo, real band, real4 affine_a0,
                         real4 affine_a1, real4 affine_a2, real4 affine_centre, real4 affine_mean,
                         __global float4* beads, __global float* values,
                         __global float* partial, int n, __local float* scratch) {
  const int i = get_global_id(0);
  const int l = get_local_id(0);
  const int size = get_local_size(0);
  float vmin = FLT_MAX, vmax = -FLT_MAX;  // neutral for work items past n
  if (i < n) {
    const real4 x = pos[i];
    const real4 x_lo = LO_AT(pos_lo, i);
    beads[i] = (float4)(convert_float3(diff_pos(x, x_lo, origin, origin_lo)), (float)x.w);
    real v = 0;
    switch (field) {
      case FIELD_SIZE:
        v = x.w;
        break;
      case FIELD_LAYER: {
        real dz = ref[i].z - z0;
#ifdef POS_COMPENSATED
        dz += ref_lo[i].z - z0_lo;
#endif
        v = floor(dz / band + (real)0.5);
        break;
      }
      case FIELD_SPEED:
        v = length(vel[i].xyz);
        break;
      case FIELD_DISPLACEMENT:
        v = length(diff_pos(x, x_lo, ref[i], LO_AT(ref_lo, i)));
        break;
      case FIELD_CONTACTS:
        v = force[i].w;  // touching neighbours + walls (forces.cl, walls.cl)
        break;
      case FIELD_ROTATION:
        v = length(omega[i].xyz);
        break;
      case FIELD_NONAFFINE: {
        const real3 r = ref[i].xyz - affine_centre.xyz;
        const real3 fit = (real3)(dot(affine_a0.xyz, r), dot(affine_a1.xyz, r),
                                  dot(affine_a2.xyz, r)) + affine_mean.xyz;
        v = length(diff_pos(x, x_lo, ref[i], LO_AT(ref_lo, i)) - fit);
        break;
      }
      case FIELD_GRAIN: {
        int grain = clumps + i;
#ifdef HAS_CLUMPS
        if (body[i] >= 0) grain = body[i];
#endif
        v = (real)grain;
        break;
      }
    }
    values[i] = (float)v;
    vmin = vmax = (float)v;
  }
  scratch[l] = vmin;
  scratch[size + l] = vmax;
  barrier(CLK_LOCAL_MEM_FENCE);
  GROUP_REDUCE(scratch, size, l, 2, MINMAX_COMBINE)
  if (l == 0) {
    partial[2 * get_group_id(0)] = scratch[0];
    partial[2 * get_group_id(0) + 1] = scratch[size];
  }
}

#ifdef HAS_WALLS
// Vector from centre x to the closest point of wall w: the geometry of
// walls.cl's wall_gap, written for one particle (the wall is known to be
// touched, so a plane needs no "behind the plane" case).
INLINE real3 to_wall(__global const real4* walls, __global const real4* wall_point,
                     __global const real4* wall_point_lo, __global const real4* wall_turn, int w,
                     real4 x, real4 x_lo) {
  const real3 d = diff_pos(wall_point[w], LO_AT(wall_point_lo, w), x, x_lo);
  const real4 head = walls[WALL_RECORD * w];
  real3 nrm = walls[WALL_RECORD * w + 1].xyz;
  real4 au = walls[WALL_RECORD * w + 2];
  const real4 av = walls[WALL_RECORD * w + 3];
#ifdef HAS_TILT
  real3 axis = au.xyz;  // a tilting wall as it stands
  tilt_axes(wall_turn[w].x, av.xyz, &nrm, &axis);
  au.xyz = axis;
#endif
  if (head.w == (real)0) {
    const real s = -dot(d, nrm);
    return -s * nrm;
  }
  const real u = clamp(-dot(d, au.xyz), -au.w, au.w);
  const real v = clamp(-dot(d, av.xyz), -av.w, av.w);
  return d + (u * au.xyz + v * av.xyz);
}
#endif

// Appends one segment (2 float4: a and |F_n|, b and the kind, 0 for a bead
// pair and 1 for a wall contact) if there is room; the counter counts all.
INLINE void emit(__global float4* segments, volatile __global int* counter, int capacity,
                 real3 a, real3 b, real fn, float kind) {
  const int at = atomic_inc(counter);
  if (at >= capacity) return;
  segments[2 * at] = (float4)(convert_float3(a), (float)fn);
  segments[2 * at + 1] = (float4)(convert_float3(b), kind);
}

// |F . e| for the unit vector along d (|F| if d vanishes).
INLINE real normal_part(real3 f, real3 d) {
  const real len = length(d);
  return len > (real)0 ? fabs(dot(f, d)) / len : length(f);
}

// Per particle i: a segment for each touching pair it owns (partners j > i,
// the upper part of its list, as in forces.cl) and, when nwalls > 0, for
// each wall it touches. Share slot (plane 0): the partner's force, w = 1 when
// touching; wall_force slot (walls.cl): the force on the wall, w = 1 when
// touching. partial[3g..3g+2]: contacts, sum and max of |F_n| over group g.
__kernel void pack_contacts(__global const real4* pos, __global const real4* pos_lo,
                            __global const uint* up_off, __global const int* nbr,
                            __global const int* nbr_upper,
                            __global const real4* pair_force, __global const real4* walls,
                            __global const real4* wall_point,
                            __global const real4* wall_point_lo,
                            __global const real4* wall_turn,
                            __global const int* wall_near, __global const uint* wall_off,
                            __global const real4* wall_force, real4 origin, real4 origin_lo,
                            __global float4* segments, volatile __global int* counter,
                            int capacity, __global real* partial, int n, int nwalls,
                            __local real* scratch) {
  const int i = get_global_id(0);
  const int l = get_local_id(0);
  const int size = get_local_size(0);
  real count = 0, sum = 0, most = 0;
  if (i < n) {
    const real4 x = pos[i];
    const real4 x_lo = LO_AT(pos_lo, i);
    const real3 a = diff_pos(x, x_lo, origin, origin_lo);
    const int upper = nbr_upper[i];
    for (int k = 0; k < upper; ++k) {
      const int slot = SLOT(up_off, i, k);
      const real4 f = pair_force[2 * slot];  // the force record of the slot's shares
      if (f.w == (real)0) continue;  // listed, not touching
      const int j = nbr[slot];
      const real4 y = pos[j];
      const real4 y_lo = LO_AT(pos_lo, j);
      const real fn = normal_part(f.xyz, diff_pos(y, y_lo, x, x_lo));
      emit(segments, counter, capacity, a, diff_pos(y, y_lo, origin, origin_lo), fn, 0.0f);
      count += 1;
      sum += fn;
      most = fmax(most, fn);
    }
#ifdef HAS_WALLS
    const int mask = wall_near[i];
    for (int w = 0; w < nwalls; ++w) {
      if (!((mask >> w) & 1)) continue;
      const real4 f = wall_force[WALL_SLOT(wall_off, i, mask, w)];
      if (f.w == (real)0) continue;
      const real3 t = to_wall(walls, wall_point, wall_point_lo, wall_turn, w, x, x_lo);
      const real fn = normal_part(f.xyz, t);
      emit(segments, counter, capacity, a, a + t, fn, 1.0f);
      count += 1;
      sum += fn;
      most = fmax(most, fn);
    }
#endif
  }
  scratch[l] = count;
  scratch[size + l] = sum;
  scratch[2 * size + l] = most;
  barrier(CLK_LOCAL_MEM_FENCE);
#define STATS_COMBINE(a, b, r) a = (r) == 2 ? fmax(a, b) : a + b
  GROUP_REDUCE(scratch, size, l, 3, STATS_COMBINE)
#undef STATS_COMBINE
  if (l == 0)
    for (int r = 0; r < 3; ++r) partial[3 * get_group_id(0) + r] = scratch[r * size];
}
