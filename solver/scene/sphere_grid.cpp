// A uniform hash grid of spheres (see sphere_grid.h).
#include "solver/scene/sphere_grid.h"

#include <algorithm>
#include <cmath>

namespace simsols {

SphereGrid::SphereGrid(double cell_size, size_t expected_spheres)
    : inv_cell_(cell_size > 0 && std::isfinite(cell_size) ? 1.0 / cell_size : 1.0) {
  cells_.reserve(expected_spheres);
}

SphereGrid::Cell SphereGrid::cell_of(const Vec3& p) const {
  // Clamped far beyond any sensible scene, only to keep the cast defined.
  constexpr double kLimit = 1e15;
  auto c = [&](double x) {
    return static_cast<std::int64_t>(std::clamp(std::floor(x * inv_cell_), -kLimit, kLimit));
  };
  return {c(p[0]), c(p[1]), c(p[2])};
}

size_t SphereGrid::CellHash::operator()(const Cell& c) const {
  std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull;
  h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  return static_cast<size_t>(h ^ (h >> 29));
}

void SphereGrid::insert(int index, const Vec3& center) { cells_[cell_of(center)].push_back(index); }

}  // namespace simsols
