// periodic.cl — the periodic cell (HAS_PERIODIC; docs/periodic-cell.md).
//
// The specimen fills a parallelepiped, the cell, repeated in all three
// directions: its edges are the columns of H (upper triangular, LAMMPS'
// triclinic convention: a = (Lx, 0, 0), b = (xy, Ly, 0), c = (xz, yz, Lz)),
// its lowest corner at c0. Every separation is taken to the nearest image
// (minimum image): d -> H (s - rint(s)) with s = H^-1 d, which is the
// nearest image whenever |d| is below half the cell's smallest width, as
// the host checks (solver/core/periodic_box.h).
//
// The cell deforms with a homogeneous velocity gradient L (the host's
// stress or strain control sets it between steps). The particles carry
// their velocity relative to that field, u = v - L (x - c0) (the SLLOD
// equations of Evans & Morriss, 1990):
//   x += (u + L (x - c0)) dt,   du/dt = F/m - L u
// so a particle at rest in the flow has u = 0, the image of a partner
// across the boundary moves at u_j + L d relative to the cell's field at
// i, and no particle is ever moved by hand except when a rebuild wraps it
// back into the cell (wrap_positions: a lattice vector, which minimum
// images do not see). Positions stay absolute (double precision only: a
// separation across the cell is formed from coordinates a cell apart).
//
// The cell record (layout.h, CELL_*) holds H, H^-1, L, the affine map
// since the last list build minus I as it will stand after this step
// (the skin check, integrate.cl), the corner and the grid's cell counts.
// The grid (grid.cl) is laid over the cell's fractional coordinates, each
// direction cut in as many cells as its width holds cut-off lengths, with
// neighbouring cells taken modulo those counts.

#ifdef HAS_PERIODIC
#ifdef POS_COMPENSATED
#error "the periodic cell runs in double precision (SIMSOLS_DOUBLE)"
#endif

// The 3x3 matrix at cell[at] (row-major) times v.
INLINE real3 cell_apply(__global const real* cell, int at, real3 v) {
  __global const real* m = cell + at;
  return (real3)(m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
                 m[6] * v.x + m[7] * v.y + m[8] * v.z);
}
INLINE real3 cell_corner(__global const real* cell) {
  return (real3)(cell[CELL_CORNER], cell[CELL_CORNER + 1], cell[CELL_CORNER + 2]);
}
INLINE real3 min_image(__global const real* cell, real3 d) {
  const real3 s = cell_apply(cell, CELL_HINV, d);
  return cell_apply(cell, CELL_H, s - rint(s));
}

// The same on lanes (forces.cl).
INLINE v3 lane_apply(__global const real* cell, int at, v3 v) {
  __global const real* m = cell + at;
  return V3(m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
            m[6] * v.x + m[7] * v.y + m[8] * v.z);
}
INLINE v3 lane_min_image(__global const real* cell, v3 d) {
  const v3 s = lane_apply(cell, CELL_HINV, d);
  return lane_apply(cell, CELL_H, V3(s.x - rint(s.x), s.y - rint(s.y), s.z - rint(s.z)));
}

INLINE int3 grid_counts(__global const real* cell) {
  return (int3)((int)cell[CELL_GRID], (int)cell[CELL_GRID + 1], (int)cell[CELL_GRID + 2]);
}
// The grid cell of position x: its fractional coordinates in [0, 1) cut
// into the grid's counts.
INLINE int3 fractional_cell_of(__global const real* cell, real3 x) {
  real3 s = cell_apply(cell, CELL_HINV, x - cell_corner(cell));
  s -= floor(s);
  const int3 n = grid_counts(cell);
  const int3 c = convert_int3_rtn(s * (real3)((real)n.x, (real)n.y, (real)n.z));
  return clamp(c, (int3)(0), n - 1);
}
INLINE int3 wrap_grid_cell(__global const real* cell, int3 c) {
  const int3 n = grid_counts(cell);
  return (c + n) % n;
}
#endif

// At a list rebuild, before the grid: every particle outside the cell is
// moved back by the lattice vector that brings it in.
__kernel void wrap_positions(__global real4* pos, __global const real* cell, int n) {
#ifdef HAS_PERIODIC
  const int i = get_global_id(0);
  if (i >= n) return;
  real4 x = pos[i];
  const real3 k = floor(cell_apply(cell, CELL_HINV, x.xyz - cell_corner(cell)));
  if (k.x != 0 || k.y != 0 || k.z != 0) {
    x.xyz -= cell_apply(cell, CELL_H, k);
    pos[i] = x;
  }
#endif
}
