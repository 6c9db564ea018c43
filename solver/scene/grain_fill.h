// Filling a solid with overlapping spheres: a clump template from any
// solid (docs/specimens.md, "Grain templates").
//
// The solid comes as a VoxelBody (voxel_body.h). Each inside cell is the
// centre of a candidate sphere, as large as fits inside: its Euclidean
// distance to the nearest outside cell centre (the exact transform of
// Felzenszwalb and Huttenlocher, Theory of Computing 8, 2012, run along x,
// y and z in turn) less half a cell, the surface lying between the two
// centres. The filler then picks spheres greedily, each time the candidate
// that covers the most inside cells not yet covered: covering is
// submodular, so the "lazy greedy" order (a heap of stale gains,
// recomputed only for the top) picks exactly what the plain greedy would,
// at a fraction of the cost. Large spheres shifted by a few cells often
// win over small ones in the corners: the union then covers more of the
// solid for the same number of spheres, which is the measure here. It
// stops at the first of: the coverage asked
// for, the most spheres allowed, or the best candidate smaller than the
// smallest radius allowed.
//
// Only the centres of maximal balls are candidates: a cell whose ball lies
// inside a neighbour's (the neighbour's radius exceeds its own by at least
// their distance) can never cover more, so the candidates shrink from the
// solid's volume to its medial surface.
//
// Fidelity is stated on the same cells: `coverage` is the fraction of the
// solid's cells inside some sphere. The spheres are inscribed (none
// reaches past the surface by more than half a cell), so the union's
// volume against the solid's (grain_templates.h reports both) says the
// rest. A grain's contacts see the union of its spheres: these say how far
// the grain the solver sees is from the solid asked for.
#pragma once

#include <vector>

#include "solver/scene/clump.h"
#include "solver/scene/voxel_body.h"

namespace simsols {

struct FillOptions {
  int max_spheres = 16;            // at most this many spheres, [1, 64]
  double coverage = 0.95;          // stop once this fraction of the solid is covered, (0, 1]
  double min_radius_ratio = 0.15;  // no sphere smaller than this times the largest that fits, (0, 1]
};

struct FillResult {
  std::vector<ClumpSphere> spheres;  // in the VoxelBody's frame (m)
  double coverage = 0;               // fraction of the solid's cells inside the spheres
};

// Throws std::invalid_argument for options out of range or a body with no
// inside cell.
FillResult fill_with_spheres(const VoxelBody& body, const FillOptions& options);

// Distance (m) from each cell's centre to the nearest centre of a cell
// whose flag is `to`: 0 for those cells themselves; every cell of the grid
// counts, and the grid's outside is not a `to` cell. A grid without any
// `to` cell gives +infinity everywhere.
std::vector<double> distance_to(const VoxelBody& body, bool to);

}  // namespace simsols
