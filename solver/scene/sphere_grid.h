// A uniform hash grid of spheres for O(1) neighbour queries, used where
// particles are placed on the host (generators, specimens, overlap checks).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "solver/common/vec3.h"

namespace simsols {

// Uniform grid of spheres for O(1) neighbour queries. for_each_near and
// any_near visit the 27 cells around a point, so there the cell size must
// be at least the largest diameter stored or queried; any_within visits as
// many as its reach needs, with cells of any size. Without bounds the
// cells are hashed; over a known box that holds every centre stored they
// are a dense array of cell lists (the DEM's linked cells: no hashing, a
// few times faster on a million spheres), where that takes at most
// kDenseCellsPerSphere cells per expected sphere. In what order a query
// visits the spheres is not part of the contract.
class SphereGrid {
 public:
  static constexpr size_t kDenseCellsPerSphere = 8;
  explicit SphereGrid(double cell_size, size_t expected_spheres = 0);
  SphereGrid(double cell_size, size_t expected_spheres, const Vec3& lo, const Vec3& hi);
  void insert(int index, const Vec3& center);
  bool dense() const { return !head_.empty(); }
  // Calls f(index) for every stored sphere in the 27 cells around `center`.
  template <class F>
  void for_each_near(const Vec3& center, F&& f) const {
    any_near(center, [&](int i) {
      f(i);
      return false;
    });
  }
  // True as soon as pred(index) is for a stored sphere in the 27 cells
  // around `center` (the rest unvisited): a placement's rejection test.
  template <class Pred>
  bool any_near(const Vec3& center, Pred&& pred) const {
    return any_within(center, 0, std::forward<Pred>(pred));
  }
  // The same over every cell within `reach` of `center` (at least the 27
  // around it): with cells smaller than the largest diameter, a sphere of
  // radius r finds all it may touch with reach = r + the largest radius,
  // far fewer candidates than cells one largest diameter wide give when
  // the sizes are graded.
  template <class Pred>
  bool any_within(const Vec3& center, double reach, Pred&& pred) const {
    const std::int64_t span =
        std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(reach * inv_cell_)));
    if (dense()) {
      const std::array<std::int64_t, 3> c = dense_cell(center);
      std::array<std::int64_t, 3> from{}, to{};
      for (int k = 0; k < 3; ++k)
        from[k] = std::max<std::int64_t>(0, c[k] - span), to[k] = std::min(dims_[k] - 1, c[k] + span);
      for (std::int64_t x = from[0]; x <= to[0]; ++x)
        for (std::int64_t y = from[1]; y <= to[1]; ++y)
          for (std::int64_t z = from[2]; z <= to[2]; ++z)
            for (int i = head_[static_cast<size_t>((x * dims_[1] + y) * dims_[2] + z)]; i >= 0;
                 i = next_[static_cast<size_t>(i)])
              if (pred(i)) return true;
      return false;
    }
    const Cell c = cell_of(center);
    for (std::int64_t dx = -span; dx <= span; ++dx)
      for (std::int64_t dy = -span; dy <= span; ++dy)
        for (std::int64_t dz = -span; dz <= span; ++dz) {
          auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells_.end()) continue;
          for (int i : it->second)
            if (pred(i)) return true;
        }
    return false;
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
  std::array<std::int64_t, 3> dense_cell(const Vec3& p) const;
  double inv_cell_;
  std::unordered_map<Cell, std::vector<int>, CellHash> cells_;
  // dense: the box's corner, its cells per axis, each cell's last sphere
  // (-1: none) and each sphere's previous one in its cell
  Vec3 lo_{};
  std::array<std::int64_t, 3> dims_{};
  std::vector<int> head_, next_;
};

}  // namespace simsols
