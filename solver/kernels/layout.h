// layout.h — the host–kernel contract, in the common subset of C++ and
// OpenCL C: what each slot of a buffer that both sides read or write
// holds. The kernels see it first in the program (solver/kernels/
// CMakeLists.txt embeds it before common.cl); the host includes it. A slot
// is named here once, never as a bare number on either side.
#ifndef SIMSOLS_KERNELS_LAYOUT_H
#define SIMSOLS_KERNELS_LAYOUT_H

#ifdef __cplusplus
namespace simsols {
#endif

// State::flags, FLAG_SLOTS ints: the neighbour-list bookkeeping the host
// reads every few steps (pipeline.cpp, detect_contacts) and the runaway
// mark the Guard reads (guard.h).
enum FlagSlot {
  FLAG_REBUILD = 0,        // 1: a particle moved more than skin/4 since the last build
  FLAG_LONGEST_LIST = 1,   // the longest list asked for when one exceeded MAX_CAP (neighbors.cl)
  FLAG_MAX_SPEED2 = 2,     // the largest |v|^2 since the last check (float bits, atomic max)
  FLAG_LATE = 3,           // 1: a particle moved more than skin/2: the lists were stale
  FLAG_RUNAWAY_FIRST = 4,  // the lowest runaway particle (atomic min; INT_MAX when none)
  FLAG_RUNAWAY_WHAT = 5,   // bit 0 not finite, bit 1 too fast
  FLAG_RUNAWAY_COUNT = 6,  // how many were marked
  FLAG_SLOTS = 8
};

// One pair coefficient record (Model::pack_pairs, contact_law.cl's
// pair_coefficients), PAIR_RECORD reals per pair of materials: the base
// record, and the capillary bridge's after it (HAS_CAPILLARY).
enum PairSlot {
  PAIR_E_STAR = 0,             // E*, Pa
  PAIR_G_STAR = 1,             // G*, Pa
  PAIR_GAMMA_N = 2,            // the normal damping ratio
  PAIR_MU_S = 3,               // sliding friction
  PAIR_MU_R = 4,               // rolling friction, m
  PAIR_KT_RATIO = 5,           // sqrt(6 G*/E*)
  PAIR_BASE_REALS = 6,         // the base record's values (slots 6, 7 pad it to 8)
  PAIR_CAP_TENSION = 8,        // gamma cos(theta), N/m
  PAIR_CAP_VOLUME = 9,         // liquid volume, m^3
  PAIR_CAP_RUPTURE = 10,       // rupture distance, m
  PAIR_CAP_REALS = 3,          // the capillary record's values (slot 11 pads it)
  PAIR_RECORD_BASE = 8,        // PAIR_RECORD without capillary bridges
  PAIR_RECORD_CAPILLARY = 12   // and with them
};

// State::cell, CELL_REALS reals: the periodic cell as the kernels read it
// (periodic.cl; written by the host each step, solver/core/periodic_box.h).
// 3x3 matrices row-major. Zeros in scenes without a periodic cell.
enum CellSlot {
  CELL_H = 0,         // the cell's edges as columns, m
  CELL_HINV = 9,      // H^-1, 1/m
  CELL_GRAD = 18,     // the velocity gradient L (dv_a/dx_b at [a][b]), 1/s
  CELL_STRETCH = 27,  // the affine map since the last list build, minus I, after this step
  CELL_CORNER = 36,   // c0, the cell's lowest corner (device frame), m
  CELL_GRID = 39,     // the grid's cell counts along a, b, c
  CELL_SINCE_BUILD = 42,  // the affine map since the last list build (host only)
  CELL_REALS = 51
};

#ifdef __cplusplus
}  // namespace simsols
#endif

#endif  // SIMSOLS_KERNELS_LAYOUT_H
