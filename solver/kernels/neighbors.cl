// neighbors.cl — Verlet neighbour lists with a skin (stage: detect contacts, part 2).
//
// Each particle i keeps the sorted list of particles j != i with
// |x_j - x_i| < r_i + r_j + skin (a "full" list: the pair appears in both
// lists and each side computes the contact; no atomics, deterministic sums).
// Every list slot carries the contact's history (tangential spring, elastic
// rolling torque: HIST_PLANES records, none when no slot needs history). On a rebuild
// the springs are carried over from the previous list by a merge join on j,
// so contact history survives every rebuild. The list is rebuilt when some
// particle has moved more than skin/2 since the last build (integrate.cl).
//
// Each list holds its upper part (partners j > i, sorted; nbr_upper[i] of
// them) in slots 0.. and then its lower part (j < i, sorted). Each pair is
// computed once, by its lower particle, from the upper part of its list, so
// slot q of consecutive particles is consecutive memory in the interleaved
// layout; build_mirrors tells the upper particle where to collect its share. flags[1] receives the largest list length requested when a list
// overflows its capacity; the host then grows the capacity and rebuilds.

#define MAX_CAP 256

__kernel void build_neighbors(__global const real4* pos POS_LO_CARG,
                              __global const uint* count, __global const uint* start,
                              __global const int* sorted,
                              __global const int* old_count, __global const int* old_upper,
                              __global const int* old_nbr, __global const real4* old_spring,
                              __global int* nbr_count, __global int* nbr, __global real4* spring,
                              __global int* nbr_upper,
                              __global real4* pos_build, __global volatile int* flags,
                              real inv_cell, real skin, uint table, int cap, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const real4 pi = pos[i];
  const int3 ci = cell_of(pi.xyz, inv_cell);

  int list[MAX_CAP];
  int len = 0;
  int wanted = 0;
  uint seen[27];
  int nseen = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const uint b = hash_cell(ci + (int3)(dx, dy, dz), table);
        bool dup = false;
        for (int s = 0; s < nseen; ++s) dup = dup || (seen[s] == b);
        if (dup) continue;
        seen[nseen++] = b;
        const uint s0 = start[b];
        const uint s1 = s0 + count[b];
        for (uint s = s0; s < s1; ++s) {
          const int j = sorted[s];
          if (j == i) continue;
          const real4 pj = pos[j];
          const real3 d = rel_pos(pi, pj LO(i) LO(j));
          const real cut = pi.w + pj.w + skin;
          if (dot(d, d) >= cut * cut) continue;
          ++wanted;
          if (len >= cap) continue;
          // insertion keeps the list sorted by j: deterministic order
          int k = len++;
          while (k > 0 && list[k - 1] > j) { list[k] = list[k - 1]; --k; }
          list[k] = j;
        }
      }
  if (wanted > cap) atomic_max(&flags[1], wanted);

  // Store the upper part (j > i, where i owns the pair and its spring) first,
  // then the lower part; both stay sorted. Springs of the upper part are
  // carried over from the old upper part by a merge join on j.
  int lower = 0;
  while (lower < len && list[lower] < i) ++lower;
  const int upper = len - lower;
  const int old_up = old_upper[i];
  int o = 0;
  for (int u = 0; u < upper; ++u) {
    const int j = list[lower + u];
    while (o < old_up && old_nbr[NBR(i, o, n, cap)] < j) ++o;
    const int found = o < old_up && old_nbr[NBR(i, o, n, cap)] == j;
    nbr[NBR(i, u, n, cap)] = j;
    // every history plane the compiled slots declare (plane p at p * n * cap)
    for (int p = 0; p < HIST_PLANES; ++p)
      spring[(size_t)p * n * cap + NBR(i, u, n, cap)] =
          found ? old_spring[(size_t)p * n * cap + NBR(i, o, n, cap)] : (real4)(0);
  }
  for (int t = 0; t < lower; ++t) nbr[NBR(i, upper + t, n, cap)] = list[t];
  nbr_count[i] = len;
  nbr_upper[i] = upper;
  pos_build[i] = pi;
}

// For every lower partner j < i of particle i (list entries k >= upper[i]),
// the slot of i in j's list, where j computed the pair (see forces.cl).
__kernel void build_mirrors(__global const int* nbr_count, __global const int* nbr,
                            __global const int* nbr_upper, __global int* mirror, int cap, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const int len = nbr_count[i];
  for (int k = nbr_upper[i]; k < len; ++k) {
    const int j = nbr[NBR(i, k, n, cap)];
    // i > j lies in the upper, sorted part of j's list: binary search
    int lo = 0, hi = nbr_upper[j] - 1;
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (nbr[NBR(j, mid, n, cap)] < i) lo = mid + 1; else hi = mid;
    }
    mirror[NBR(i, k, n, cap)] = NBR(j, lo, n, cap);
  }
}
