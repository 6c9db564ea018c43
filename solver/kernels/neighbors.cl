// neighbors.cl — Verlet neighbour lists with a skin (stage: detect contacts, part 2).
//
// Each particle i lists the particles j != i with
// |x_j - x_i| < r_i + r_j + skin, in two sorted parts: the upper part
// (j > i) and the lower part (j < i). Each pair is computed once, by its
// lower particle, from its upper part (forces.cl): an upper slot carries
// the partner's id, the contact's history (tangential spring, elastic
// rolling torque: HIST_PLANES records, none when no slot needs history) and
// the partner's share of the force; a lower slot only the partner's id and
// the mirror, the upper slot where that partner left this particle's share.
//
// Layout: sliced lists (the SELL-C format of Kreutzer et al., SIAM J. Sci.
// Comput. 36, 2014). Particles come in slices of SLICE consecutive indices;
// a slice keeps its lists as one block of width x SLICE slots, width being
// its longest list, slot k of its particles side by side (SLOT, common.cl),
// so the lanes of a work item, or neighbouring GPU threads, read
// consecutive memory. Memory follows the pairs actually listed, not a fixed
// capacity per particle. A rebuild runs in four passes:
//   count_neighbors  each list's lengths (nbr_count, nbr_upper)
//   slice_widths     each slice's block size; a prefix sum (grid.cl's scan)
//                    turns them into the offsets up_off, lo_off
//   build_neighbors  the lists, the history carried over from the previous
//                    upper list by a merge join on j, so contact history
//                    survives every rebuild; a lower slot receives its
//                    partner's id in the mirror buffer
//   build_mirrors    replaces each lower slot's partner id by its mirror, in
//                    place (a lower slot's id is needed only to find it)
// The previous list's history waits in the share buffer during a rebuild
// (the shares are dead then: written and read within one step).
// flags[FLAG_LONGEST_LIST] receives the longest list asked for when one exceeds MAX_CAP.

#define MAX_CAP 256

// The sorted list of particle i's neighbours within the skin (up to
// MAX_CAP of them; returns how many there are).
INLINE int find_neighbors(int i, real4 pi POS_LO_CARG_FN, __global const uint* count,
                          __global const uint* start, __global const int* sorted,
                          __global const real4* pos, __global const int* body,
                          __global const real* cell, real inv_cell, real skin, uint table,
                          int* list) {
#ifdef HAS_GROUPS
  const int own = body[i];  // a clump's members, a membrane's beads never touch each other
#endif
  const int3 ci = grid_cell(pi.xyz, inv_cell, cell);
  int len = 0;
  int wanted = 0;
  uint seen[27];
  int nseen = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const uint b = grid_bucket(ci + (int3)(dx, dy, dz), table, cell);
        bool dup = false;
        for (int s = 0; s < nseen; ++s) dup = dup || (seen[s] == b);
        if (dup) continue;
        seen[nseen++] = b;
        const uint s0 = start[b];
        const uint s1 = s0 + count[b];
        for (uint s = s0; s < s1; ++s) {
          const int j = sorted[s];
          if (j == i) continue;
#ifdef HAS_GROUPS
          if (own >= 0 && body[j] == own) continue;
#endif
          const real4 pj = pos[j];
#ifdef HAS_PERIODIC
          const real3 d = min_image(cell, rel_pos(pi, pj LO(i) LO(j)));
#else
          const real3 d = rel_pos(pi, pj LO(i) LO(j));
#endif
          const real cut = pi.w + pj.w + skin;
          if (dot(d, d) >= cut * cut) continue;
          ++wanted;
          if (len >= MAX_CAP) continue;
          // insertion keeps the list sorted by j: deterministic order
          int k = len++;
          while (k > 0 && list[k - 1] > j) { list[k] = list[k - 1]; --k; }
          list[k] = j;
        }
      }
  return wanted;
}

// Entries of the sorted `list` below i: the lower part's length.
INLINE int lower_part(const int* list, int len, int i) {
  int lower = 0;
  while (lower < len && list[lower] < i) ++lower;
  return lower;
}

__kernel void count_neighbors(__global const real4* pos POS_LO_CARG,
                              __global const uint* count, __global const uint* start,
                              __global const int* sorted, __global int* nbr_count,
                              __global int* nbr_upper, __global volatile int* flags,
                              __global const int* body, __global const real* cell,
                              real inv_cell, real skin, uint table, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  int list[MAX_CAP];
  const int wanted = find_neighbors(i, pos[i] POS_LO_PASS, count, start, sorted, pos, body,
                                    cell, inv_cell, skin, table, list);
  if (wanted > MAX_CAP) atomic_max(&flags[FLAG_LONGEST_LIST], wanted);
  const int len = min(wanted, MAX_CAP);
  nbr_count[i] = len;
  nbr_upper[i] = len - lower_part(list, len, i);
}

// Slice g's block sizes in slots (its longest upper and lower parts, times
// SLICE); entry `slices` is 0, so the exclusive prefix sum ends with the
// totals.
__kernel void slice_widths(__global const int* nbr_count, __global const int* nbr_upper,
                           __global uint* up_width, __global uint* lo_width, int n, int slices) {
  const int g = get_global_id(0);
  if (g > slices) return;
  int up = 0, lo = 0;
  for (int i = g * SLICE; g < slices && i < min(n, (g + 1) * SLICE); ++i) {
    up = max(up, nbr_upper[i]);
    lo = max(lo, nbr_count[i] - nbr_upper[i]);
  }
  up_width[g] = (uint)(up * SLICE);
  lo_width[g] = (uint)(lo * SLICE);
}

// Springs of the upper part come from the previous upper part (old_*, its
// history planes at p * old_stride in old_hist) by a merge join on j.
__kernel void build_neighbors(__global const real4* pos POS_LO_CARG,
                              __global const uint* count, __global const uint* start,
                              __global const int* sorted, __global const uint* old_up_off,
                              __global const int* old_upper, __global const int* old_nbr,
                              __global const real* old_hist, int old_stride,
                              __global const uint* up_off, __global const uint* lo_off,
                              __global const int* nbr_upper, __global int* nbr,
                              __global int* mirror, __global real* spring, int stride,
                              __global float4* pos_build, __global const int* body,
                              __global const real* cell, real inv_cell, real skin, uint table,
                              int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const real4 pi = pos[i];
  int list[MAX_CAP];
  const int len = min(MAX_CAP, find_neighbors(i, pi POS_LO_PASS, count, start, sorted, pos, body,
                                              cell, inv_cell, skin, table, list));
  const int upper = nbr_upper[i];
  const int lower = len - upper;
  const int old_up = old_upper[i];
  int o = 0;
  for (int u = 0; u < upper; ++u) {
    const int j = list[lower + u];
    while (o < old_up && old_nbr[SLOT(old_up_off, i, o)] < j) ++o;
    const int found = o < old_up && old_nbr[SLOT(old_up_off, i, o)] == j;
    const int slot = SLOT(up_off, i, u);
    nbr[slot] = j;
    // every history plane the compiled slots declare (planes of 4 x stride
    // reals, records by component: SLOT_REAL)
    const int from = found ? SLOT(old_up_off, i, o) : 0;
    for (int p = 0; p < HIST_PLANES; ++p)
      for (int c = 0; c < 4; ++c)
        spring[4 * (size_t)p * stride + SLOT_REAL(slot, c)] =
            found ? old_hist[4 * (size_t)p * old_stride + SLOT_REAL(from, c)] : (real)0;
  }
  for (int t = 0; t < lower; ++t) mirror[SLOT(lo_off, i, t)] = list[t];  // the partner, for now
  pos_build[i] = convert_float4(pi);
}

// For every lower partner j < i of particle i (its id left in the slot by
// build_neighbors), the upper slot of i in j's list, where j computed the
// pair (see forces.cl). Each work item rewrites only its own lower slots.
__kernel void build_mirrors(__global const int* nbr_count, __global const int* nbr_upper,
                            __global const uint* up_off, __global const int* nbr,
                            __global const uint* lo_off, __global int* mirror, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const int lower = nbr_count[i] - nbr_upper[i];
  for (int k = 0; k < lower; ++k) {
    const int j = mirror[SLOT(lo_off, i, k)];
    // i > j lies in the upper, sorted part of j's list: binary search
    int lo = 0, hi = nbr_upper[j] - 1;
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (nbr[SLOT(up_off, j, mid)] < i) lo = mid + 1; else hi = mid;
    }
    mirror[SLOT(lo_off, i, k)] = SLOT(up_off, j, lo);
  }
}
