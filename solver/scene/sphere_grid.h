// A uniform hash grid of spheres for O(1) neighbour queries, used where
// particles are placed on the host (generators, specimens, overlap checks).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "solver/common/vec3.h"

namespace simsols {

// Uniform hash grid of spheres for O(1) neighbour queries; the cell size
// must be at least the largest diameter stored or queried.
class SphereGrid {
 public:
  explicit SphereGrid(double cell_size, size_t expected_spheres = 0);
  void insert(int index, const Vec3& center);
  // Calls f(index) for every stored sphere in the 27 cells around `center`.
  template <class F>
  void for_each_near(const Vec3& center, F&& f) const {
    const Cell c = cell_of(center);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells_.end()) continue;
          for (int i : it->second) f(i);
        }
  }

 private:
  struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell&) const = default;
  };
  struct CellHash {
    size_t operator()(const Cell& c) const;
  };
  Cell cell_of(const Vec3& p) const;
  double inv_cell_;
  std::unordered_map<Cell, std::vector<int>, CellHash> cells_;
};

}  // namespace simsols
