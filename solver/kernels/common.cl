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
#ifdef SIMSOLS_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
typedef double3 real3;
typedef double4 real4;
typedef double8 real8;
#else
typedef float real;
typedef float3 real3;
typedef float4 real4;
typedef float8 real8;
#define POS_COMPENSATED 1
#endif

#ifdef NBR_INTERLEAVED
#define NBR(i, k, n, cap) ((k) * (n) + (i))
#else
#define NBR(i, k, n, cap) ((i) * (cap) + (k))
#endif

// Per-pair coefficient record (real8), see contact_model.h:
//   s0 E*   s1 G*   s2 gamma_n   s3 mu_s   s4 mu_r
#define PAIR_ESTAR(c) ((c).s0)
#define PAIR_GSTAR(c) ((c).s1)
#define PAIR_GAMMA(c) ((c).s2)
#define PAIR_MUS(c) ((c).s3)
#define PAIR_MUR(c) ((c).s4)

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
