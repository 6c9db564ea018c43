// common.cl — scalar type, layout macros and compensated positions.
//
// Build options (set by cl_program.cpp from the Scene, never by hand):
//   SIMSOLS_DOUBLE     real = double; otherwise real = float
//   HAS_GRAVITY, HAS_DAMPING, HAS_FRICTION, HAS_ROLLING, HAS_WALLS
//   NBR_INTERLEAVED    neighbour slot k of particle i at k*n+i (GPU) instead of i*cap+k (CPU)
//
// Positions in float runs are stored as an unevaluated sum hi + lo of two
// floats ("double-float"): hi is a normal float position relative to the scene
// origin and lo carries the rounding error of every update. Relative
// positions (hi_j - hi_i) + (lo_j - lo_i) are then accurate to ~1e-7 of the
// separation instead of ~1e-7 of the distance to the origin, so slow motions
// (1e-10 m per step) are not lost and overlaps of 1e-7 m are resolved far
// from the origin. In double runs lo is absent.
// No fused multiply-add contraction: the same expression rounds the same way
// in every code path (scalar, SIMD, remainder loops), which keeps results
// independent of list length, work-group layout and skin.
#pragma OPENCL FP_CONTRACT OFF

#ifdef SIMSOLS_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
typedef double3 real3;
typedef double4 real4;
#else
typedef float real;
typedef float3 real3;
typedef float4 real4;
#define POS_COMPENSATED 1
#endif

#ifdef NBR_INTERLEAVED
#define NBR(i, k, n, cap) ((k) * (n) + (i))
#else
#define NBR(i, k, n, cap) ((i) * (cap) + (k))
#endif

// Per-pair coefficient record: 8 reals, see contact_law.cl (PAIR).

// Wall record: four real4 per wall:
//   [0] point (xyz, relative to origin)  w: shape (0 plane, 1 rectangle)
//   [1] normal                           w: material index
//   [2] axis_u                           w: half_u
//   [3] axis_v                           w: half_v
#define WALL_RECORD 4

// Separation vector b - a of two compensated positions.
inline real3 rel_pos(real4 a, real4 b
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

#ifdef POS_COMPENSATED
// (hi, lo) += d with Knuth's two-sum: no rounding error is lost.
inline void add_compensated(real4* hi, float4* lo, real3 d) {
  const real3 a = (*hi).xyz;
  const real3 b = d + (*lo).xyz;
  const real3 s = a + b;
  const real3 bb = s - a;
  const real3 err = (a - (s - bb)) + (b - bb);
  (*hi).xyz = s;
  (*lo).xyz = err;
}
#define POS_LO_ARG , __global float4* pos_lo
#define POS_LO_CARG , __global const float4* pos_lo
#define LO(i) , pos_lo[i]
#else
#define POS_LO_ARG , __global const real4* pos_lo_unused
#define POS_LO_CARG , __global const real4* pos_lo_unused
#define LO(i)
#endif

// ---------------------------------------------------------------------------
// Scalar 3-vectors for the hot kernels. OpenCL's built-in vector types are
// not widened by LLVM's loop vectoriser, which is what turns PoCL's loop over
// work items into SIMD code on CPUs; a struct of three scalars is split into
// scalars by the compiler and vectorises across work items. On GPUs both
// forms compile to the same scalar code. Records stay 4-wide in memory
// (xyz + one packed constant) and are read component by component.
typedef struct { real x, y, z; } v3;

inline v3 V3(real x, real y, real z) { v3 r; r.x = x; r.y = y; r.z = z; return r; }
inline v3 v_add(v3 a, v3 b) { return V3(a.x + b.x, a.y + b.y, a.z + b.z); }
inline v3 v_sub(v3 a, v3 b) { return V3(a.x - b.x, a.y - b.y, a.z - b.z); }
inline v3 v_mul(real s, v3 a) { return V3(s * a.x, s * a.y, s * a.z); }
inline v3 v_neg(v3 a) { return V3(-a.x, -a.y, -a.z); }
inline real v_dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline v3 v_cross(v3 a, v3 b) {
  return V3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
inline v3 v_select(bool c, v3 a, v3 b) { return V3(c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z); }
inline v3 v_zero() { return V3(0, 0, 0); }

inline v3 load3(__global const real* p, int i) { return V3(p[4 * i], p[4 * i + 1], p[4 * i + 2]); }
inline real load_w(__global const real* p, int i) { return p[4 * i + 3]; }
inline void store4(__global real* p, int i, v3 v, real w) {
  p[4 * i] = v.x; p[4 * i + 1] = v.y; p[4 * i + 2] = v.z; p[4 * i + 3] = w;
}

// Separation x_b - x_a of two compensated positions, scalar form.
#ifdef POS_COMPENSATED
inline v3 rel3(__global const real* pos, __global const float* lo, int a, int b) {
  return V3((pos[4 * b] - pos[4 * a]) + (lo[4 * b] - lo[4 * a]),
            (pos[4 * b + 1] - pos[4 * a + 1]) + (lo[4 * b + 1] - lo[4 * a + 1]),
            (pos[4 * b + 2] - pos[4 * a + 2]) + (lo[4 * b + 2] - lo[4 * a + 2]));
}
#define POS_LO_SARG , __global const float* restrict pos_lo
#define REL3(a, b) rel3(pos, pos_lo, a, b)
#else
#define POS_LO_SARG , __global const real* pos_lo_unused
#define REL3(a, b) v_sub(load3(pos, b), load3(pos, a))
#endif
