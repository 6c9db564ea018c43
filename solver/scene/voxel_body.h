// A solid on a voxel grid: what a grain template is filled from
// (docs/specimens.md, "Grain templates").
//
// Every template, whatever its source (a named shape from its aspect ratio
// and angularity, or a surface mesh), is first turned into this one form: a
// box of cubic cells, each inside the solid or not (its centre's test).
// grain_fill.h then fills the inside with overlapping spheres. Keeping the
// two apart lets each source be tested on its own (the voxel volume against
// the solid's exact volume) and the filler once for all of them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "solver/common/vec3.h"

namespace simsols {

struct VoxelBody {
  int nx = 0, ny = 0, nz = 0;  // cells along x, y, z
  double cell = 0;             // m, the cells' edge
  Vec3 origin{};               // m, the corner of cell (0, 0, 0): cell (i, j, k) has its centre at
                               // origin + cell * (i + 0.5, j + 0.5, k + 0.5)
  std::vector<std::uint8_t> inside;  // 1 where the cell's centre is inside; index i + nx * (j + ny * k)

  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
  }
  // The cell (i, j, k) at `index`: index()'s inverse.
  std::array<int, 3> cell_at(std::size_t index) const {
    const std::size_t layer = static_cast<std::size_t>(nx) * ny;
    return {static_cast<int>(index % nx), static_cast<int>((index / nx) % ny), static_cast<int>(index / layer)};
  }
  Vec3 centre(int i, int j, int k) const {
    return {origin[0] + cell * (i + 0.5), origin[1] + cell * (j + 0.5), origin[2] + cell * (k + 0.5)};
  }
  // m^3: the inside cells' volume.
  double volume() const;
};

}  // namespace simsols
