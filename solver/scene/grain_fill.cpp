#include "solver/scene/grain_fill.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>

namespace simsols {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The squared distance transform of one line (Felzenszwalb & Huttenlocher
// 2012): d[q] = min_p (q - p)^2 + f[p], through the lower envelope of the
// parabolas rooted at the finite samples. f and d are in cells^2.
void transform_line(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
                    std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;
    while (k >= 0) {
      const int p = v[k];
      const double s = ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p));
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kInf : ((f[q] + double(q) * q) - (f[v[k - 1]] + double(v[k - 1]) * v[k - 1])) /
                               (2.0 * (q - v[k - 1]));
  }
  if (k < 0) {
    std::fill(d.begin(), d.end(), kInf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (j < k && z[j + 1] < q) ++j;
    const double dq = q - v[j];
    d[q] = dq * dq + f[v[j]];
  }
}

// Runs transform_line along one axis of the grid (stride between
// neighbours, count along the axis) for every line of that axis.
void transform_axis(const VoxelBody& b, std::vector<double>& g, int axis) {
  const int n[3] = {b.nx, b.ny, b.nz};
  const std::size_t stride[3] = {1, static_cast<std::size_t>(b.nx),
                                 static_cast<std::size_t>(b.nx) * b.ny};
  const int len = n[axis], u = (axis + 1) % 3, w = (axis + 2) % 3;
  std::vector<double> f(len), d(len), z(len + 1);
  std::vector<int> v(len);
  for (int a = 0; a < n[u]; ++a)
    for (int c = 0; c < n[w]; ++c) {
      const std::size_t base = a * stride[u] + c * stride[w];
      for (int q = 0; q < len; ++q) f[q] = g[base + q * stride[axis]];
      transform_line(f, d, v, z);
      for (int q = 0; q < len; ++q) g[base + q * stride[axis]] = d[q];
    }
}

struct Candidate {
  double gain;  // cells it would newly cover (stale: an upper bound)
  std::size_t cell;
  bool operator<(const Candidate& o) const { return gain < o.gain; }
};

// Visits the cells whose centres lie within `radius` of cell c's centre.
template <class F>
void for_cells_in_ball(const VoxelBody& b, std::size_t c, double radius, F&& visit) {
  const auto [i0, j0, k0] = b.cell_at(c);
  const double r = radius / b.cell, r2 = r * r;
  const int reach = static_cast<int>(std::floor(r));
  for (int k = std::max(0, k0 - reach); k <= std::min(b.nz - 1, k0 + reach); ++k)
    for (int j = std::max(0, j0 - reach); j <= std::min(b.ny - 1, j0 + reach); ++j)
      for (int i = std::max(0, i0 - reach); i <= std::min(b.nx - 1, i0 + reach); ++i) {
        const double di = i - i0, dj = j - j0, dk = k - k0;
        if (di * di + dj * dj + dk * dk <= r2) visit(b.index(i, j, k));
      }
}

// True unless a neighbour's ball holds cell c's: r(n) >= r(c) + |n - c|
// (to a hundredth of a cell, the transform's round-off).
bool maximal_ball(const VoxelBody& b, const std::vector<double>& radius, std::size_t c) {
  const auto [i0, j0, k0] = b.cell_at(c);
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int i = i0 + di, j = j0 + dj, k = k0 + dk;
        if ((di | dj | dk) == 0 || i < 0 || j < 0 || k < 0 || i >= b.nx || j >= b.ny || k >= b.nz)
          continue;
        const double step = std::sqrt(double(di * di + dj * dj + dk * dk)) * b.cell;
        if (radius[b.index(i, j, k)] >= radius[c] + step - 0.01 * b.cell) return false;
      }
  return true;
}

void check_options(const VoxelBody& body, const FillOptions& o) {
  if (o.max_spheres < 1 || o.max_spheres > 64)
    throw std::invalid_argument("max_spheres = " + std::to_string(o.max_spheres) + " is out of range [1, 64]");
  if (!(o.coverage > 0 && o.coverage <= 1))
    throw std::invalid_argument("coverage = " + std::to_string(o.coverage) + " is out of range (0, 1]");
  if (!(o.min_radius_ratio > 0 && o.min_radius_ratio <= 1))
    throw std::invalid_argument("min_radius_ratio = " + std::to_string(o.min_radius_ratio) +
                                " is out of range (0, 1]");
  if (std::find(body.inside.begin(), body.inside.end(), 1) == body.inside.end())
    throw std::invalid_argument("the solid has no inside cell: make it larger or the cells smaller");
}

}  // namespace

std::vector<double> distance_to(const VoxelBody& body, bool to) {
  std::vector<double> g(body.inside.size());
  for (std::size_t c = 0; c < g.size(); ++c) g[c] = (body.inside[c] != 0) == to ? 0 : kInf;
  for (int axis = 0; axis < 3; ++axis) transform_axis(body, g, axis);
  for (double& x : g) x = std::sqrt(x) * body.cell;
  return g;
}

FillResult fill_with_spheres(const VoxelBody& body, const FillOptions& o) {
  check_options(body, o);
  std::vector<double> radius = distance_to(body, false);
  double largest = 0;
  for (std::size_t c = 0; c < radius.size(); ++c) {
    radius[c] = body.inside[c] ? std::max(radius[c] - 0.5 * body.cell, 0.5 * body.cell) : 0;
    largest = std::max(largest, radius[c]);
  }
  const double smallest = o.min_radius_ratio * largest;
  std::priority_queue<Candidate> heap;
  for (std::size_t c = 0; c < radius.size(); ++c)
    if (body.inside[c] && radius[c] >= smallest && maximal_ball(body, radius, c))
      heap.push({4.19 * std::pow(radius[c] / body.cell + 1, 3), c});  // > any ball's cell count
  std::size_t solid = 0;
  for (std::uint8_t f : body.inside) solid += f;
  std::vector<std::uint8_t> covered(body.inside.size(), 0);
  std::size_t covered_solid = 0;
  FillResult out;
  while (!heap.empty() && static_cast<int>(out.spheres.size()) < o.max_spheres &&
         covered_solid < o.coverage * solid) {
    Candidate top = heap.top();
    heap.pop();

    double gain = 0;
    for_cells_in_ball(body, top.cell, radius[top.cell],
                      [&](std::size_t c) { gain += body.inside[c] && !covered[c]; });
    if (gain <= 0) continue;
    if (!heap.empty() && gain < heap.top().gain) {  // stale: requeue with its true gain
      heap.push({gain, top.cell});
      continue;
    }
    for_cells_in_ball(body, top.cell, radius[top.cell], [&](std::size_t c) {
      covered_solid += body.inside[c] && !covered[c];
      covered[c] = 1;
    });
    const auto [i, j, k] = body.cell_at(top.cell);
    out.spheres.push_back({body.centre(i, j, k), radius[top.cell]});
  }
  out.coverage = double(covered_solid) / double(solid);
  return out;
}

}  // namespace simsols
