// grid.cl — uniform grid, counting-sorted by cell (stage: detect contacts, part 1).
//
// Cells are cubes of side cell_size >= largest diameter + skin, so all
// neighbours of a particle lie in its 27 surrounding cells. Cell coordinates
// are hashed into a table of `table` buckets (a power of two ~ 2N): memory
// grows with N, not with the domain volume. A bucket may hold several cells;
// the distance test in build_neighbors filters those out.
//
// Sorting is a counting sort: count particles per bucket (grid_count), an
// exclusive prefix sum in three passes (scan_chunks, scan_totals,
// scan_apply), then scatter (grid_scatter). The order inside a bucket depends
// on atomics and is NOT deterministic; build_neighbors sorts each list by
// particle index, so nothing downstream depends on it.

INLINE int3 cell_of(real3 x, real inv_cell) {
  return convert_int3_rtn(x * inv_cell);
}

INLINE uint hash_cell(int3 c, uint table) {
  const uint h = ((uint)c.x * 73856093u) ^ ((uint)c.y * 19349663u) ^ ((uint)c.z * 83492791u);
  return h & (table - 1u);
}

// In a periodic cell (periodic.cl) the grid is laid over the cell's
// fractional coordinates and wraps: grid_cell and grid_bucket are cell_of
// and hash_cell of either kind of scene.
INLINE int3 grid_cell(real3 x, real inv_cell, __global const real* cell) {
#ifdef HAS_PERIODIC
  return fractional_cell_of(cell, x);
#else
  return cell_of(x, inv_cell);
#endif
}
INLINE uint grid_bucket(int3 c, uint table, __global const real* cell) {
#ifdef HAS_PERIODIC
  c = wrap_grid_cell(cell, c);
#endif
  return hash_cell(c, table);
}

__kernel void grid_clear(__global uint* count, uint table) {
  const uint b = get_global_id(0);
  if (b < table) count[b] = 0u;
}

__kernel void grid_count(__global const real4* pos, __global uint* bucket, __global uint* slot,
                         __global uint* count, __global const real* cell, real inv_cell,
                         uint table, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const uint b = grid_bucket(grid_cell(pos[i].xyz, inv_cell, cell), table, cell);
  bucket[i] = b;
  slot[i] = atomic_inc(&count[b]);
}

// Exclusive prefix sum of count[0..table) into start[], in `chunks` chunks.
__kernel void scan_chunks(__global const uint* count, __global uint* chunk_sum, uint table,
                          uint chunk_len) {
  const uint c = get_global_id(0);
  const uint b0 = c * chunk_len;
  if (b0 >= table) { chunk_sum[c] = 0u; return; }
  const uint b1 = min(b0 + chunk_len, table);
  uint s = 0u;
  for (uint b = b0; b < b1; ++b) s += count[b];
  chunk_sum[c] = s;
}

__kernel void scan_totals(__global uint* chunk_sum, uint chunks) {
  if (get_global_id(0) != 0) return;
  uint s = 0u;
  for (uint c = 0; c < chunks; ++c) {
    const uint v = chunk_sum[c];
    chunk_sum[c] = s;
    s += v;
  }
}

__kernel void scan_apply(__global const uint* count, __global const uint* chunk_sum,
                         __global uint* start, uint table, uint chunk_len) {
  const uint c = get_global_id(0);
  const uint b0 = c * chunk_len;
  if (b0 >= table) return;
  const uint b1 = min(b0 + chunk_len, table);
  uint s = chunk_sum[c];
  for (uint b = b0; b < b1; ++b) {
    const uint v = count[b];  // read first: start may be count (in place)
    start[b] = s;
    s += v;
  }
}

__kernel void grid_scatter(__global const uint* bucket, __global const uint* slot,
                           __global const uint* start, __global int* sorted, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  sorted[start[bucket[i]] + slot[i]] = i;
}
