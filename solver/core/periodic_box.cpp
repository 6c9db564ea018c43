#include "solver/core/periodic_box.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "solver/common/errors.h"
#include "solver/common/number_text.h"
#include "solver/core/observe.h"
#include "solver/core/pipeline.h"
#include "solver/core/state.h"
#include "solver/kernels/layout.h"

namespace simsols {
namespace {

using M = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
M eig(const Mat3& m) { return Eigen::Map<const M>(m.data()); }
Mat3 arr(const M& m) {
  Mat3 out;
  Eigen::Map<M>(out.data()) = m;
  return out;
}

// The step's map I + L dt.
Mat3 step_map(const CellNow& c, double dt) { return arr(M::Identity() + eig(c.grad) * dt); }

// Grid cells along each edge: as many as the width holds cut-off lengths.
std::array<int, 3> grid_counts(const Mat3& h, double cut) {
  const Vec3 w = cell_widths(h);
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::floor(w[a] / cut)));
  return n;
}

void put(std::vector<double>& rec, int at, const Mat3& m) { std::copy(m.begin(), m.end(), rec.begin() + at); }
Mat3 take(const std::vector<double>& rec, int at) {
  Mat3 m;
  std::copy(rec.begin() + at, rec.begin() + at + 9, m.begin());
  return m;
}

// Stops a run whose cell became too thin for minimum images.
void check_widths(const Model& m, const Mat3& h) {
  const Vec3 w = cell_widths(h);
  const double thinnest = std::min({w[0], w[1], w[2]});
  if (thinnest >= 2 * m.cell_size()) return;
  const Scene& s = m.scene();
  throw SceneError("out_of_range", s.source_path.empty() ? s.name : s.source_path, 0,
                   "periodic_cell",
                   "the periodic cell's thinnest width fell to " + shortest_number(thinnest) +
                       " m, below twice the cut-off (" + shortest_number(2 * m.cell_size()) +
                       " m: the largest diameter plus the skin); use more particles or less strain");
}

}  // namespace

Mat3 identity3() { return arr(M::Identity()); }
Mat3 mul3(const Mat3& a, const Mat3& b) { return arr(eig(a) * eig(b)); }
Vec3 apply3(const Mat3& m, const Vec3& v) {
  const Eigen::Vector3d r = eig(m) * Eigen::Vector3d(v[0], v[1], v[2]);
  return {r[0], r[1], r[2]};
}
Mat3 inverse3(const Mat3& m) { return arr(eig(m).inverse()); }
double det3(const Mat3& m) { return eig(m).determinant(); }

Vec3 cell_widths(const Mat3& h) {
  const Vec3 a{h[0], h[3], h[6]}, b{h[1], h[4], h[7]}, c{h[2], h[5], h[8]};
  const double v = std::abs(det3(h));
  return {v / norm(cross(b, c)), v / norm(cross(c, a)), v / norm(cross(a, b))};
}

Vec3 min_image(const Mat3& h, const Vec3& d) {
  Vec3 s = apply3(inverse3(h), d);
  for (double& x : s) x -= std::nearbyint(x);
  return apply3(h, s);
}

Mat3 fold_tilts(Mat3 h) {
  // c -= round(yz / Ly) b, then c -= round(xz / Lx) a, b -= round(xy / Lx) a
  const double kc = std::nearbyint(h[5] / h[4]);
  h[5] -= kc * h[4];
  h[2] -= kc * h[1];
  h[2] -= std::nearbyint(h[2] / h[0]) * h[0];
  h[1] -= std::nearbyint(h[1] / h[0]) * h[0];
  return h;
}

bool upper_triangular(const Mat3& m) { return m[3] == 0 && m[6] == 0 && m[7] == 0; }

void write_cell(const Model& m, State& s) {
  if (!m.config().periodic) return;
  const std::vector<double> rec = cell_record(m, s.cell_now);
  m.device().write(s.cell.get(), rec.size() * sizeof(double), rec.data());
}

std::vector<double> cell_record(const Model& m, const CellNow& c) {
  std::vector<double> rec(CELL_REALS, 0.0);
  put(rec, CELL_H, c.h);
  put(rec, CELL_HINV, inverse3(c.h));
  put(rec, CELL_GRAD, c.grad);
  Mat3 stretch = mul3(step_map(c, m.dt()), c.since_build);  // after the coming step
  for (int k : {0, 4, 8}) stretch[k] -= 1;
  put(rec, CELL_STRETCH, stretch);
  for (int a = 0; a < 3; ++a) rec[CELL_CORNER + a] = c.corner[a];
  const std::array<int, 3> n = grid_counts(c.h, m.cell_size());
  for (int a = 0; a < 3; ++a) rec[CELL_GRID + a] = n[a];
  put(rec, CELL_SINCE_BUILD, c.since_build);
  return rec;
}

void read_cell(const Model& m, State& s) {
  if (!m.config().periodic) return;
  const std::vector<double> rec = read_reals(m, s.cell, CELL_REALS);
  CellNow& c = s.cell_now;
  c.h = take(rec, CELL_H);
  c.grad = take(rec, CELL_GRAD);
  c.since_build = take(rec, CELL_SINCE_BUILD);
  for (int a = 0; a < 3; ++a) c.corner[a] = rec[CELL_CORNER + a];
}

void cell_rebuilt(const Model& m, State& s) {
  if (!m.config().periodic) return;
  s.cell_now.since_build = identity3();
  write_cell(m, s);
}

void move_cell(const Model& m, State& s) {
  if (!m.config().periodic) return;
  CellNow& c = s.cell_now;
  const Mat3 step = step_map(c, m.dt());
  c.h = fold_tilts(mul3(step, c.h));
  c.since_build = mul3(step, c.since_build);
  check_widths(m, c.h);
  // a pair's separation drifts by (F - I) d with the cell, |d| below the
  // cut-off: past skin/8 the lists are rebuilt (the particles' own travel
  // has the rest of the skin: integrate.cl)
  M drift = eig(mul3(step, c.since_build)) - M::Identity();
  if (drift.norm() * m.cell_size() > m.skin() / 8) request_rebuild(m, s);
  write_cell(m, s);
}

}  // namespace simsols
