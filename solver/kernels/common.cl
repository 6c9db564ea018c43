// common.cl — scalar type, layout macros and compensated positions.
//
// Build options (set by cl_program.cpp from the Scene, never by hand):
//   SIMSOLS_DOUBLE     real = double; otherwise real = float
//   HAS_GRAVITY, HAS_DAMPING, HAS_FRICTION, HAS_ROLLING, HAS_WALLS   effect slots
//   HAS_ROLLING_SPRING  rolling = spring_dashpot (else constant torque)
//   HAS_CAPILLARY       cohesion = capillary (pair records of 12 reals)
//   HAS_FLUID           fluid = drag (integrate.cl)
//   HIST_PLANES         per-contact history records (real4) each list or wall slot carries,
//                       0 = no history at all; HIST_CONTACT, HIST_ROLL the planes of the
//                       sub-models that keep history (cl_program.h's table; what each
//                       holds: contact_law.cl, "Per-contact history")
//   PAIR_RECORD         reals per pair coefficient record (8, or 12 with HAS_CAPILLARY)
//   HAS_SERVO, HAS_CLUMPS  servo-controlled walls, clumps (clumps.cl)
//   HAS_MEMBRANE       a membrane of bonded beads (membrane.cl)
//   HAS_TILT           some wall may turn about its axis_v (walls.cl, wall_turn)
//   SLICE, LANES       list slice width and particles per work item (below)
//   SERVO_IN_FINISH    CPUs: the walls' step at the end of finish_particles (integrate.cl)
//   PREFETCH_SHARES    CPUs: finish_particles prefetches the partners' shares (forces.cl)
//
// Positions in float runs are stored as an unevaluated sum hi + lo of two
// floats ("double-float"): hi is a normal float position relative to the scene
// origin and lo carries the rounding error of every update. Relative
// positions (hi_j - hi_i) + (lo_j - lo_i) are then accurate to ~1e-7 of the
// separation instead of ~1e-7 of the distance to the origin, so slow motions
// (1e-10 m per step) are not lost and overlaps of 1e-7 m are resolved far
// from the origin. In double runs lo is absent.
// Helpers are always inlined (PoCL otherwise keeps some as calls in hot loops).
#define INLINE inline __attribute__((always_inline))

// No fused multiply-add contraction: the same expression rounds the same way
// in every code path (scalar, SIMD, remainder loops), which keeps results
// independent of list length, work-group layout and skin.
#pragma OPENCL FP_CONTRACT OFF

#ifdef SIMSOLS_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define REAL_NAME double
typedef double real;
typedef double3 real3;
typedef double4 real4;
#define to_real3(v) convert_double3(v)
#else
#define REAL_NAME float
typedef float real;
typedef float3 real3;
typedef float4 real4;
#define to_real3(v) (v)
#define POS_COMPENSATED 1
#endif

// Neighbour-list slot k of particle i in the sliced layout (neighbors.cl):
// particles in slices of SLICE consecutive indices, slice g's block of
// width x SLICE slots at off[g], slot k of its particles side by side.
// state.h's list_slot() is the host's copy of this formula.
#ifndef SLICE
#define SLICE 8
#endif
#define SLOT(off, i, k) ((int)(off)[(i) / SLICE] + (k) * SLICE + (i) % SLICE)
// Component c (0..3) of slot s's record in the history planes (`spring`):
// a slice's records are stored component by component, the x of its SLICE
// slots side by side, then y, z and w, so a work item's lanes (consecutive
// slots of one slice) load and store each component as one vector. The
// share buffer keeps whole records (store_shares): its readers (collect_one)
// come one slot at a time, from anywhere. state.h's slot_real() is the
// host's copy.
#define SLOT_REAL(s, c) ((size_t)(s) / SLICE * (4 * SLICE) + (c) * SLICE + (size_t)(s) % SLICE)
// Wall w's slot of particle i (walls.cl): rank r of bit w among the bits of
// its near-wall mask. observe.h's WallSlots::slot() is the host's copy.
#define WALL_SLOT(off, i, mask, w) SLOT(off, i, (int)popcount((mask) & ((1 << (w)) - 1)))

// Particles of one group never touch each other (neighbors.cl): a clump's
// members, a membrane's beads (Model's body buffer).
#if defined(HAS_CLUMPS) || defined(HAS_MEMBRANE)
#define HAS_GROUPS 1
#endif

// Per-pair coefficient record: PAIR_RECORD reals, see contact_law.cl.
#ifndef PAIR_RECORD
#define PAIR_RECORD 8
#endif
#ifndef HIST_PLANES
#define HIST_PLANES 0
#endif
#if defined(HAS_FRICTION) || defined(HAS_DAMPING)
#define HAS_CONTACT_RECORD 1
#endif
// rolling = constant_torque shares its cap among a particle's contacts of
// the previous step (forces.cl): their counts are kept (State::touching).
#if defined(HAS_ROLLING) && !defined(HAS_ROLLING_SPRING)
#define HAS_SHARED_ROLLING_CAP 1
#endif

// Wall record: four real4 per wall:
//   [0] point (xyz, relative to origin)  w: shape (0 plane, 1 rectangle)
//   [1] normal                           w: material index
//   [2] axis_u                           w: half_u
//   [3] axis_v                           w: half_v
#define WALL_RECORD 4

#ifdef HAS_TILT
// A tilting wall's normal n and axis_u turned by t about its axis_v
// (walls.cl): both are normal to av, so Rodrigues' formula is
// R x = x cos t + (av x x) sin t. The render packing uses it too.
INLINE void tilt_axes(real t, real3 av, real3* n, real3* au) {
  const real c = cos(t), s = sin(t);
  *n = c * *n + s * cross(av, *n);
  *au = c * *au + s * cross(av, *au);
}
#endif

// Separation vector b - a of two compensated positions.
INLINE real3 rel_pos(real4 a, real4 b
#ifdef POS_COMPENSATED
                     , float4 a_lo, float4 b_lo
#endif
) {
  real3 d = b.xyz - a.xyz;
#ifdef POS_COMPENSATED
  d += b_lo.xyz - a_lo.xyz;
#endif
  return d;
}

// The neighbour lists' validity, after a particle travelled sqrt(moved2)
// since the last build (integrate.cl, clumps.cl): beyond skin/4 the host
// rebuilds them (FLAG_REBUILD, layout.h); beyond skin/2 they were stale
// (FLAG_LATE), a contact may have been missed.
INLINE void mark_travel(__global volatile int* flags, real moved2, real skin) {
  if (moved2 > (real)0.0625 * skin * skin) flags[FLAG_REBUILD] = 1;
  if (moved2 > (real)0.25 * skin * skin) flags[FLAG_LATE] = 1;
}

#ifdef POS_COMPENSATED
// (hi, lo) += d with Knuth's two-sum: no rounding error is lost.
INLINE void add_compensated(real4* hi, float4* lo, real3 d) {
  const real3 a = (*hi).xyz;
  const real3 b = d + (*lo).xyz;
  const real3 s = a + b;
  const real3 bb = s - a;
  const real3 err = (a - (s - bb)) + (b - bb);
  (*hi).xyz = s;
  (*lo).xyz = err;
}
// x += d for a position whose low part is lo_at[i] (a particle's or a
// clump's): the drift of every integrator.
INLINE void drift_compensated(real4* x, __global float4* lo_at, int i, real3 d) {
  float4 lo = lo_at[i];
  add_compensated(x, &lo, d);
  lo_at[i] = lo;
}
#define DRIFT(x, lo_at, i, d) drift_compensated(x, lo_at, i, d)
#define POS_LO_ARG , __global float4* pos_lo
#define POS_LO_CARG , __global const float4* pos_lo
#define POS_LO_SARG , __global const float* restrict pos_lo
#define POS_LO_SARG_FN , __global const float* pos_lo
#define POS_LO_CARG_FN , __global const float4* pos_lo
#define POS_LO_PASS , pos_lo
#define LO(i) , pos_lo[i]
#else
#define DRIFT(x, lo_at, i, d) ((*(x)).xyz += (d))
#define POS_LO_ARG , __global const real4* pos_lo_unused
#define POS_LO_CARG , __global const real4* pos_lo_unused
#define POS_LO_SARG , __global const real* pos_lo_unused
#define POS_LO_SARG_FN
#define POS_LO_CARG_FN
#define POS_LO_PASS
#define LO(i)
#endif

// ---------------------------------------------------------------------------
// Lanes: the contact kernels process LANES particles per work item (LANES is
// a build option: 1 on GPUs, 8 or 16 on CPUs). A `lane` holds one value for
// each of them (real, real8 or real16) and maps onto SIMD registers; the
// contact law is written once on lanes. Memory stays per particle: lanes are
// gathered from and scattered to the 4-wide particle records.
// Conditions are lane masks (`lmask`); SEL(c, a, b) picks a where c holds.
#ifndef LANES
#define LANES 1
#endif
#define CAT_(a, b) a##b
#define CAT(a, b) CAT_(a, b)
#if LANES == 1
typedef real lane;
typedef int lmask;
typedef int lmask_elem;
#define SEL(c, a, b) ((c) ? (a) : (b))
#define LANE_LOAD(p) ((p)[0])
#define LANE_STORE(v, p) ((p)[0] = (v))
#else
typedef CAT(REAL_NAME, LANES) lane;
#ifdef SIMSOLS_DOUBLE
typedef CAT(long, LANES) lmask;
typedef long lmask_elem;
#else
typedef CAT(int, LANES) lmask;
typedef int lmask_elem;
#endif
#define SEL(c, a, b) select((b), (a), (c))
#define LANE_LOAD(p) CAT(vload, LANES)(0, (p))
#define LANE_STORE(v, p) CAT(vstore, LANES)((v), 0, (p))
#endif

// 3-vectors of lanes (a struct of scalars: compilers split it into registers).
typedef struct { lane x, y, z; } v3;

INLINE v3 V3(lane x, lane y, lane z) { v3 r; r.x = x; r.y = y; r.z = z; return r; }
INLINE v3 v_add(v3 a, v3 b) { return V3(a.x + b.x, a.y + b.y, a.z + b.z); }
INLINE v3 v_sub(v3 a, v3 b) { return V3(a.x - b.x, a.y - b.y, a.z - b.z); }
INLINE v3 v_mul(lane s, v3 a) { return V3(s * a.x, s * a.y, s * a.z); }
INLINE v3 v_neg(v3 a) { return V3(-a.x, -a.y, -a.z); }
INLINE lane v_dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
INLINE v3 v_cross(v3 a, v3 b) {
  return V3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
INLINE v3 v_sel(lmask c, v3 a, v3 b) { return V3(SEL(c, a.x, b.x), SEL(c, a.y, b.y), SEL(c, a.z, b.z)); }
INLINE v3 v_zero() { return V3((lane)0, (lane)0, (lane)0); }

// Component `c` of the 4-wide record of each lane's particle idx[l].
INLINE lane gather(__global const real* p, const int* idx, int c) {
  real t[LANES];
  #pragma unroll
  for (int l = 0; l < LANES; ++l) t[l] = p[4 * idx[l] + c];
  return LANE_LOAD(t);
}
// The rolling cap's divisor (contact_law.cl) is the larger of the contact
// counts of the last step of a pair's two particles, at least 1 (for a wall
// contact, the particle's own): this is each lane's particle's part of it.
INLINE lane cap_count(__global const int* touching, const int* ii) {
  real t[LANES];
  #pragma unroll
  for (int l = 0; l < LANES; ++l) t[l] = (real)max(1, touching[ii[l]]);
  return LANE_LOAD(t);
}
// The step's contact count of particle i (its force record's w), kept for
// the next step's cap; nothing unless the cap is shared.
INLINE void keep_contact_count(__global int* touching, int i, real count) {
#ifdef HAS_SHARED_ROLLING_CAP
  touching[i] = (int)count;
#endif
}
// All four components of each lane's record, one 4-wide load per lane.
typedef struct { v3 xyz; lane w; } Lane4;
INLINE Lane4 gather4(__global const real* p, const int* idx) {
  real x[LANES], y[LANES], z[LANES], w[LANES];
#pragma unroll
  for (int l = 0; l < LANES; ++l) {
    const real4 r = vload4(idx[l], p);
    x[l] = r.x; y[l] = r.y; z[l] = r.z; w[l] = r.w;
  }
  Lane4 out;
  out.xyz = V3(LANE_LOAD(x), LANE_LOAD(y), LANE_LOAD(z));
  out.w = LANE_LOAD(w);
  return out;
}
INLINE v3 gather3(__global const real* p, const int* idx) { return gather4(p, idx).xyz; }
#ifdef POS_COMPENSATED
INLINE lane gather_lo(__global const float* p, const int* idx, int c) {
  real t[LANES];
  #pragma unroll
  for (int l = 0; l < LANES; ++l) t[l] = p[4 * idx[l] + c];
  return LANE_LOAD(t);
}
#endif
// Writes (v, w) to record idx[l] of every lane with keep[l] != 0.
INLINE void scatter4(__global real* p, const int* idx, const int* keep, v3 v, lane w) {
  real x[LANES], y[LANES], z[LANES], q[LANES];
  LANE_STORE(v.x, x); LANE_STORE(v.y, y); LANE_STORE(v.z, z); LANE_STORE(w, q);
  #pragma unroll
  for (int l = 0; l < LANES; ++l) {
    if (!keep[l]) continue;
    __global real* r = p + 4 * idx[l];
    r[0] = x[l]; r[1] = y[l]; r[2] = z[l]; r[3] = q[l];
  }
}
// The records of consecutive slots s0, s0 + 1, ... (one per lane, in one
// slice), at p + SLOT_REAL(s0, 0): four vector loads or stores. Lanes that
// keep nothing store the zeros their caller selected (the slot is a slice's
// padding then, zero since the rebuild).
INLINE Lane4 load_slots(__global const real* p, size_t at) {
  Lane4 r;
  r.xyz = V3(LANE_LOAD(p + at), LANE_LOAD(p + at + SLICE), LANE_LOAD(p + at + 2 * SLICE));
  r.w = LANE_LOAD(p + at + 3 * SLICE);
  return r;
}
INLINE void store_slots(__global real* p, size_t at, v3 v, lane w) {
  LANE_STORE(v.x, p + at);
  LANE_STORE(v.y, p + at + SLICE);
  LANE_STORE(v.z, p + at + 2 * SLICE);
  LANE_STORE(w, p + at + 3 * SLICE);
}
// The partners' shares of consecutive slots s0, s0 + 1, ... (one per lane),
// a slot's force record (f, fw) and torque record (t, tw) side by side (8
// reals: one cache line for the partner that collects them): one contiguous
// block, every lane written.
INLINE void store_shares(__global real* p, int s0, v3 f, lane fw, v3 t, lane tw) {
  real a[8][LANES];
  LANE_STORE(f.x, a[0]); LANE_STORE(f.y, a[1]); LANE_STORE(f.z, a[2]); LANE_STORE(fw, a[3]);
  LANE_STORE(t.x, a[4]); LANE_STORE(t.y, a[5]); LANE_STORE(t.z, a[6]); LANE_STORE(tw, a[7]);
  __global real* r = p + 8 * (size_t)s0;
#pragma unroll
  for (int l = 0; l < LANES; ++l)
#pragma unroll
    for (int c = 0; c < 8; ++c) r[8 * l + c] = a[c][l];
}
// A lane mask from per-lane flags.
INLINE lmask mask_of(const int* flag) {
  lmask_elem t[LANES];
  #pragma unroll
  for (int l = 0; l < LANES; ++l) t[l] = flag[l] ? (lmask_elem)-1 : (lmask_elem)0;
#if LANES == 1
  return t[0] != 0;
#else
  return LANE_LOAD(t);
#endif
}

// True when the mask holds in some lane (a uniform branch per work item).
INLINE int mask_any(lmask m) {
#if LANES == 1
  return m != 0;
#else
  return any(m);
#endif
}

// Position of each lane's particle (compensated in float runs): separations
// are formed as (hi_j - hi_i) + (lo_j - lo_i).
typedef struct { v3 hi; v3 lo; } LanePos;
INLINE LanePos gather_pos(__global const real* pos POS_LO_SARG_FN, const int* idx) {
  LanePos r;
  r.hi = gather3(pos, idx);
#ifdef POS_COMPENSATED
  r.lo = V3(gather_lo(pos_lo, idx, 0), gather_lo(pos_lo, idx, 1), gather_lo(pos_lo, idx, 2));
#else
  r.lo = v_zero();
#endif
  return r;
}
INLINE v3 separation(LanePos a, LanePos b) {
  return v_add(v_sub(b.hi, a.hi), v_sub(b.lo, a.lo));
}
