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

SphereGrid::SphereGrid(double cell_size, size_t expected_spheres, const Vec3& lo, const Vec3& hi)
    : SphereGrid(cell_size, 0) {
  std::array<std::int64_t, 3> dims{};
  double cells = 1;
  for (int k = 0; k < 3; ++k) {
    const double n = std::floor((hi[k] - lo[k]) * inv_cell_) + 1;
    if (!(n >= 1 && std::isfinite(n))) {  // no usable box: hashed
      cells_.reserve(expected_spheres);
      return;
    }
    dims[k] = static_cast<std::int64_t>(std::min(n, 1e12));
    cells *= n;
  }
  if (cells > double(kDenseCellsPerSphere * expected_spheres + 4096)) {
    cells_.reserve(expected_spheres);
    return;
  }
  lo_ = lo;
  dims_ = dims;
  head_.assign(static_cast<size_t>(cells), -1);
  next_.reserve(expected_spheres);
}

std::array<std::int64_t, 3> SphereGrid::dense_cell(const Vec3& p) const {
  std::array<std::int64_t, 3> c{};
  for (int k = 0; k < 3; ++k) {
    const double x = std::floor((p[k] - lo_[k]) * inv_cell_);  // outside the box: its edge cell
    c[k] = x >= 0 ? static_cast<std::int64_t>(std::min(x, double(dims_[k] - 1))) : 0;
  }
  return c;
}

void SphereGrid::insert(int index, const Vec3& center) {
  if (!dense()) {
    cells_[cell_of(center)].push_back(index);
    return;
  }
  const std::array<std::int64_t, 3> c = dense_cell(center);
  int& head = head_[static_cast<size_t>((c[0] * dims_[1] + c[1]) * dims_[2] + c[2])];
  if (static_cast<size_t>(index) >= next_.size()) next_.resize(static_cast<size_t>(index) + 1, -1);
  next_[static_cast<size_t>(index)] = head;
  head = index;
}

}  // namespace simsols
