#include "solver/scene/clump.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2 * kPi;

// 8-point Gauss-Legendre on [-1, 1].
constexpr std::array<double, 8> kNode = {-0.9602898564975363, -0.7966664774136267,
                                         -0.5255324099163290, -0.1834346424956498,
                                         0.1834346424956498,  0.5255324099163290,
                                         0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeight = {0.1012285362903763, 0.2223810344533745,
                                           0.3137066458778873, 0.3626837833783620,
                                           0.3626837833783620, 0.3137066458778873,
                                           0.2223810344533745, 0.1012285362903763};

// Green's theorem along the arc t in [t0, t1] of circle d, in pieces of
// at most pi/8 (where 8 Gauss points are exact to round-off for the
// degree-4 trigonometric integrands).
void add_arc(const Disk& d, double t0, double t1, DiskUnionMoments& m) {
  const int pieces = std::max(1, static_cast<int>(std::ceil((t1 - t0) / (kPi / 8))));
  const double h = (t1 - t0) / pieces;
  for (int p = 0; p < pieces; ++p)
    for (size_t g = 0; g < kNode.size(); ++g) {
      const double t = t0 + h * (p + 0.5 * (kNode[g] + 1)), w = 0.5 * h * kWeight[g];
      const double c = std::cos(t), s = std::sin(t);
      const double x = d.x + d.radius * c, y = d.y + d.radius * s;
      const double dx = -d.radius * s * w, dy = d.radius * c * w;
      m.area += 0.5 * (x * dy - y * dx);
      m.x += 0.5 * x * x * dy;
      m.y -= 0.5 * y * y * dx;
      m.xx += x * x * x / 3 * dy;
      m.yy -= y * y * y / 3 * dx;
      m.xy += 0.5 * x * x * y * dy;
    }
}

// The angles of disk i's circle that disk j covers, as [a, b] (b - a in
// (0, 2 pi)); false when j covers none of it; `whole` when j covers it all.
bool covered_by(const Disk& i, const Disk& j, bool j_first, double* a, double* b, bool* whole) {
  const double dx = j.x - i.x, dy = j.y - i.y, dist = std::hypot(dx, dy);
  *whole = false;
  if (dist == 0 && i.radius == j.radius) return *whole = j_first;  // one of twins counts
  if (dist + i.radius <= j.radius) return *whole = true;
  if (dist >= i.radius + j.radius || dist + j.radius <= i.radius) return false;
  const double phi = std::atan2(dy, dx);
  const double cos_half = (i.radius * i.radius + dist * dist - j.radius * j.radius) /
                          (2 * i.radius * dist);
  const double half = std::acos(std::clamp(cos_half, -1.0, 1.0));
  *a = phi - half;
  *b = phi + half;
  return true;
}

// The arcs of disk k's circle outside every other disk, added to m.
void add_exposed_arcs(std::span<const Disk> disks, size_t k, DiskUnionMoments& m) {
  std::vector<std::pair<double, double>> cover;
  for (size_t j = 0; j < disks.size(); ++j) {
    if (j == k || disks[j].radius <= 0) continue;
    double a = 0, b = 0;
    bool whole = false;
    if (!covered_by(disks[k], disks[j], j < k, &a, &b, &whole)) continue;
    if (whole) return;
    const double length = b - a;
    a -= kTwoPi * std::floor(a / kTwoPi);  // [0, 2 pi)
    b = a + length;
    if (b > kTwoPi) {
      cover.push_back({a, kTwoPi});
      cover.push_back({0, b - kTwoPi});
    } else {
      cover.push_back({a, b});
    }
  }
  std::sort(cover.begin(), cover.end());
  double t = 0;
  for (const auto& [a, b] : cover) {
    if (a > t) add_arc(disks[k], t, a, m);
    t = std::max(t, b);
  }
  if (t < kTwoPi) add_arc(disks[k], t, kTwoPi, m);
}

// The slice of the union at height z.
DiskUnionMoments slice(std::span<const ClumpSphere> spheres, double z, std::vector<Disk>& disks) {
  disks.clear();
  for (const ClumpSphere& s : spheres) {
    const double h = z - s.centre[2], r2 = s.radius * s.radius - h * h;
    if (r2 > 0) disks.push_back({s.centre[0], s.centre[1], std::sqrt(r2)});
  }
  return disk_union_moments(disks);
}

// Principal moments (ascending) and right-handed axes of `inertia`.
void principal_axes(MassProperties& m) {
  Eigen::Matrix3d a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a(i, j) = m.inertia[i][j];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a);
  Eigen::Matrix3d v = eig.eigenvectors();
  if (v.determinant() < 0) v.col(2) = -v.col(2);
  for (int k = 0; k < 3; ++k) {
    m.principal[k] = eig.eigenvalues()(k);
    m.axes[k] = {v(0, k), v(1, k), v(2, k)};
  }
}

// Where the slices change character: each sphere's bottom and top, and the
// lowest and highest points of each two spheres' circle of intersection
// (where their slices' circles start and stop crossing), sorted.
std::vector<double> slice_cuts(std::span<const ClumpSphere> spheres) {
  std::vector<double> cuts;
  for (size_t i = 0; i < spheres.size(); ++i) {
    const ClumpSphere& p = spheres[i];
    cuts.push_back(p.centre[2] - p.radius);
    cuts.push_back(p.centre[2] + p.radius);
    for (size_t j = i + 1; j < spheres.size(); ++j) {
      const ClumpSphere& q = spheres[j];
      const Vec3 u = {q.centre[0] - p.centre[0], q.centre[1] - p.centre[1], q.centre[2] - p.centre[2]};
      const double d = norm(u);
      if (!(d > 0) || d >= p.radius + q.radius || d <= std::abs(p.radius - q.radius)) continue;
      const double a = (d * d + p.radius * p.radius - q.radius * q.radius) / (2 * d);
      const double rho = std::sqrt(std::max(0.0, p.radius * p.radius - a * a));
      const double nz = u[2] / d, zc = p.centre[2] + a * nz;
      const double reach = rho * std::sqrt(std::max(0.0, 1 - nz * nz));
      cuts.push_back(zc - reach);
      cuts.push_back(zc + reach);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

}  // namespace

Quaternion quat_multiply(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

Vec3 quat_rotate(const Quaternion& q, const Vec3& v) {
  // v + 2 u x (u x v + w v), u = (x, y, z)
  const Vec3 u = {q[1], q[2], q[3]};
  const Vec3 t = cross(u, v);
  const Vec3 s = {t[0] + q[0] * v[0], t[1] + q[0] * v[1], t[2] + q[0] * v[2]};
  const Vec3 c = cross(u, s);
  return {v[0] + 2 * c[0], v[1] + 2 * c[1], v[2] + 2 * c[2]};
}

GrainBody grain_body(const Grain& grain) {
  std::vector<ClumpSphere> spheres;
  for (const auto& s : grain.spheres) spheres.push_back({{s[0], s[1], s[2]}, s[3]});
  GrainBody b;
  b.mass = union_mass_properties(spheres);
  Eigen::Matrix3d axes;  // columns: the principal axes in the grain's frame
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) axes(i, k) = b.mass.axes[k][i];
  const Eigen::Quaterniond q(axes);
  b.to_grain = {q.w(), q.x(), q.y(), q.z()};
  const Quaternion to_body = {q.w(), -q.x(), -q.y(), -q.z()};
  for (const ClumpSphere& s : spheres) {
    const Vec3 r = {s.centre[0] - b.mass.centroid[0], s.centre[1] - b.mass.centroid[1],
                    s.centre[2] - b.mass.centroid[2]};
    b.offsets.push_back(quat_rotate(to_body, r));
    b.radii.push_back(s.radius);
  }
  return b;
}

std::vector<double> solid_volumes(const Scene& scene) {
  std::vector<double> v(scene.particles.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = 4.0 / 3.0 * kPi * std::pow(scene.particles[i].radius, 3);
  if (scene.clumps.empty()) return v;
  std::vector<double> grain_volume;
  for (const Grain& g : scene.grains) grain_volume.push_back(grain_body(g).mass.volume);
  for (const Clump& c : scene.clumps) {
    double spheres = 0;
    for (int j = 0; j < c.count; ++j) spheres += v[c.first + j];
    const double volume = grain_volume[c.grain] * c.scale * c.scale * c.scale;
    for (int j = 0; j < c.count; ++j) v[c.first + j] *= volume / spheres;
  }
  return v;
}

Quaternion uniform_rotation(double u1, double u2, double u3) {
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return {b * std::cos(2 * kPi * u3), a * std::sin(2 * kPi * u2), a * std::cos(2 * kPi * u2),
          b * std::sin(2 * kPi * u3)};
}

double volume_equivalent_diameter(const GrainBody& body) {
  return std::cbrt(6 / kPi * body.mass.volume);
}

GrainBody scaled(const GrainBody& body, double scale) {
  if (scale == 1) return body;
  GrainBody b = body;
  const double s3 = scale * scale * scale, s5 = s3 * scale * scale;
  b.mass.volume *= s3;
  for (int i = 0; i < 3; ++i) {
    b.mass.centroid[i] *= scale;
    b.mass.principal[i] *= s5;
    for (int j = 0; j < 3; ++j) b.mass.inertia[i][j] *= s5;
  }
  for (Vec3& o : b.offsets)
    for (double& x : o) x *= scale;
  for (double& r : b.radii) r *= scale;
  return b;
}

Quaternion body_orientation(const Clump& c, const GrainBody& body) {
  return quat_multiply(c.orientation, body.to_grain);
}

void add_clump(Scene& scene, Clump c, const GrainBody& unit) {
  const GrainBody body = scaled(unit, c.scale);
  const Quaternion q = body_orientation(c, body);
  c.first = static_cast<int>(scene.particles.size());
  c.count = static_cast<int>(body.offsets.size());
  const int index = static_cast<int>(scene.clumps.size());
  for (size_t k = 0; k < body.offsets.size(); ++k) {
    const Vec3 r = quat_rotate(q, body.offsets[k]);
    const Vec3 spin = cross(c.angular_velocity, r);
    Particle p;
    p.material = c.material;
    p.radius = body.radii[k];
    p.position = {c.position[0] + r[0], c.position[1] + r[1], c.position[2] + r[2]};
    p.velocity = {c.velocity[0] + spin[0], c.velocity[1] + spin[1], c.velocity[2] + spin[2]};
    p.angular_velocity = c.angular_velocity;
    p.clump = index;
    scene.particles.push_back(p);
  }
  scene.clumps.push_back(c);
}

DiskUnionMoments disk_union_moments(std::span<const Disk> disks) {
  DiskUnionMoments m;
  for (size_t k = 0; k < disks.size(); ++k)
    if (disks[k].radius > 0) add_exposed_arcs(disks, k, m);
  return m;
}

MassProperties union_mass_properties(std::span<const ClumpSphere> spheres, int panels) {
  const std::vector<double> cuts = slice_cuts(spheres);
  double v = 0, m1[3] = {0, 0, 0}, m2[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  std::vector<Disk> disks;
  // The cuts multiply with the spheres (every pair adds its circle's
  // extremes) and the slices between them are smooth: past 8 cuts the
  // panels per cut fall so the total stays near 8 x panels (at least 2 each).
  const int intervals = std::max<int>(1, static_cast<int>(cuts.size()) - 1);
  const int per_cut = std::clamp(8 * panels / intervals, std::min(2, panels), panels);
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double h = (cuts[c + 1] - cuts[c]) / per_cut;
    if (!(h > 0)) continue;
    for (int p = 0; p < per_cut; ++p)
      for (size_t g = 0; g < kNode.size(); ++g) {
        const double z = cuts[c] + h * (p + 0.5 * (kNode[g] + 1)), w = 0.5 * h * kWeight[g];
        const DiskUnionMoments s = slice(spheres, z, disks);
        v += w * s.area;
        m1[0] += w * s.x, m1[1] += w * s.y, m1[2] += w * z * s.area;
        m2[0][0] += w * s.xx, m2[1][1] += w * s.yy, m2[2][2] += w * z * z * s.area;
        m2[0][1] += w * s.xy, m2[0][2] += w * z * s.x, m2[1][2] += w * z * s.y;
      }
  }
  MassProperties m;
  m.volume = v;
  for (int i = 0; i < 3; ++i) m.centroid[i] = m1[i] / v;
  double c[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) c[i][j] = c[j][i] = m2[i][j] - v * m.centroid[i] * m.centroid[j];
  const double trace = c[0][0] + c[1][1] + c[2][2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.inertia[i][j] = (i == j ? trace : 0) - c[i][j];
  principal_axes(m);
  return m;
}

}  // namespace simsols
