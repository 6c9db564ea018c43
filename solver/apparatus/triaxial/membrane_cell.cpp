#include "solver/apparatus/triaxial/membrane_cell.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace simsols {

std::vector<Vec3> membrane_ring(double x0, double x1, double y0, double y1, double offset, int n) {
  // the path: four sides and four quarter circles about the corners,
  // counter-clockwise from the middle of the x1 side
  const double lx = x1 - x0, ly = y1 - y0, arc = std::numbers::pi / 2 * offset;
  const double total = 2 * (lx + ly) + 4 * arc;
  const double cx[4] = {x1, x0, x0, x1}, cy[4] = {y1, y1, y0, y0};  // the corners in turn
  const double side[4] = {ly, lx, ly, lx};
  std::vector<Vec3> out;
  for (int k = 0; k < n; ++k) {
    double s = std::fmod(total * k / n + side[0] / 2, total);  // from the x1 side's start
    int q = 0;
    while (s > side[q] + arc && q < 3) s -= side[q++] + arc;
    const double a0 = std::numbers::pi / 2 * q;  // the outward normal's angle along side q
    const double nx = std::cos(a0), ny = std::sin(a0), tx = -ny, ty = nx;
    const double sx = q == 0 ? x1 : q == 1 ? x1 : q == 2 ? x0 : x0;
    const double sy = q == 0 ? y0 : q == 1 ? y1 : q == 2 ? y1 : y0;
    if (s <= side[q]) {
      out.push_back({sx + tx * s + nx * offset, sy + ty * s + ny * offset, 0});
    } else {
      const double a = a0 + (s - side[q]) / offset;
      out.push_back({cx[q] + offset * std::cos(a), cy[q] + offset * std::sin(a), 0});
    }
  }
  return out;
}

MembraneWrap wrap_cuboid(const Membrane& m, double rm, double pressure, const CuboidExtent& b) {
  const std::vector<Vec3> ring = membrane_ring(b.x0, b.x1, b.y0, b.y1, rm, m.cols);
  const double pitch = (b.z1 - b.z0 - 2 * rm) / (m.rows - 1);
  MembraneWrap w;
  for (int r = 0; r < m.rows; ++r)
    for (const Vec3& x : ring) w.positions.push_back({x[0], x[1], b.z0 + rm + r * pitch});
  double chords = 0;
  for (size_t k = 0; k < ring.size(); ++k) {
    const Vec3& a = ring[k];
    const Vec3& c = ring[(k + 1) % ring.size()];
    chords += std::hypot(c[0] - a[0], c[1] - a[1]);
  }
  const double chord = chords / double(ring.size());
  w.setting.pressure = pressure;
  w.setting.held = false;
  w.setting.rest_hoop = chord;
  w.setting.rest_axial = pitch;
  w.setting.k_hoop = m.stiffness * pitch / chord;
  w.setting.k_axial = m.stiffness * chord / pitch;
  w.setting.axis_x = 0.5 * (b.x0 + b.x1);
  w.setting.axis_y = 0.5 * (b.y0 + b.y1);
  return w;
}

namespace {

struct Ring {
  double area = 0, perimeter = 0, z = 0, bond_force = 0;  // bond_force: mean hoop pull, N
};

Ring measure_ring(const std::vector<Vec3>& x, int first, int cols, const Simulation::MembraneSetting& s) {
  Ring g;
  for (int c = 0; c < cols; ++c) {
    const Vec3& a = x[size_t(first + c)];
    const Vec3& b = x[size_t(first + (c + 1) % cols)];
    g.area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
    const double l = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    g.perimeter += std::hypot(b[0] - a[0], b[1] - a[1]);
    g.bond_force += s.k_hoop * (l - s.rest_hoop) / cols;
    g.z += a[2] / cols;
  }
  return g;
}

}  // namespace

MembraneShape measure_membrane(const std::vector<Vec3>& x, const Membrane& m, double rm, double z0,
                               double z1, const Simulation::MembraneSetting& s) {
  std::vector<Ring> rings;
  for (int r = 0; r < m.rows; ++r) rings.push_back(measure_ring(x, m.first + r * m.cols, m.cols, s));
  // the inner face of overlapping beads: the ring of centres shrunk by r_m
  const auto inner = [&](const Ring& g) {
    return g.area - g.perimeter * rm + std::numbers::pi * rm * rm;
  };
  MembraneShape out;
  // below the first ring and above the last, its own area
  out.volume = inner(rings.front()) * std::max(0.0, std::min(rings.front().z, z1) - z0) +
               inner(rings.back()) * std::max(0.0, z1 - std::max(rings.back().z, z0));
  for (size_t r = 0; r + 1 < rings.size(); ++r) {  // the area linear between rings, within [z0, z1]
    const double za = rings[r].z, zb = rings[r + 1].z;
    const double lo = std::max(za, z0), hi = std::min(zb, z1);
    if (!(hi > lo) || !(zb > za)) continue;
    const double aa = inner(rings[r]), ab = inner(rings[r + 1]);
    const auto at = [&](double z) { return aa + (ab - aa) * (z - za) / (zb - za); };
    out.volume += 0.5 * (at(lo) + at(hi)) * (hi - lo);
  }
  // the end rings are sealed to the floor and the platen: no hoop tension of their own
  out.area = out.volume / (z1 - z0);
  double hoop = 0;
  int counted = 0;
  for (size_t r = 1; r + 1 < rings.size(); ++r) {
    const double pitch = 0.5 * (rings[r + 1].z - rings[r - 1].z);
    if (!(pitch > 0)) continue;
    hoop += 2 * std::numbers::pi * rings[r].bond_force / pitch / rings[r].perimeter;
    ++counted;
  }
  out.hoop_stress = counted > 0 ? hoop / counted : 0;
  return out;
}

double membrane_axial_share(const ContactSample& sample, size_t inside, double volume, double z0) {
  double moment = 0;  // N m
  for (const ContactForce& c : sample.contacts)
    if (const auto k = boundary_contact(sample, c, inside)) moment += k->force[2] * (k->point[2] - z0);
  return volume > 0 ? moment / volume : 0;
}

double membrane_shell_share(double stiffness, double axial_strain, double area) {
  const double d = std::sqrt(4 * area / std::numbers::pi);
  return d > 0 ? 4 * stiffness * axial_strain / d : 0;
}

double inside_coordination(const ContactSample& sample, size_t inside) {
  double ends = 0;
  for (const ContactForce& c : sample.contacts)
    ends += (size_t(c.a) < inside ? 1 : 0) + (c.b >= 0 && size_t(c.b) < inside ? 1 : 0);
  return inside > 0 ? ends / double(inside) : 0;
}

}  // namespace simsols
