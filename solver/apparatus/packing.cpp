#include "solver/apparatus/packing.h"

#include <algorithm>
#include <cmath>

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Volume of the sphere below height h above its centre's plane (h in [-r, r]).
double below(double h, double r) {
  h = std::clamp(h, -r, r);
  const double cap = r + h;  // height of the segment from the sphere's bottom
  return kPi * cap * cap * (3 * r - cap) / 3;
}

// The bead pairs' sum of n n (diagonal) and their count.
std::array<double, 3> contact_fabric(const ContactSample& sample, int* pairs) {
  const ParticleSnapshot& snap = sample.beads;
  std::array<double, 3> f{};
  int n = 0;
  for (const ContactForce& c : sample.contacts) {
    if (c.b < 0) continue;
    Vec3 l{};
    double len2 = 0;
    for (int k = 0; k < 3; ++k) {
      l[k] = snap.position[c.b][k] - snap.position[c.a][k];
      len2 += l[k] * l[k];
    }
    if (len2 <= 0) continue;
    for (int k = 0; k < 3; ++k) f[k] += l[k] * l[k] / len2;
    ++n;
  }
  *pairs = n;
  return f;
}

// (15/2)(phi_zz - (phi_xx + phi_yy)/2) from contact_fabric's sums.
double anisotropy(const std::array<double, 3>& f, int pairs) {
  return pairs > 0 ? 7.5 * (f[2] - 0.5 * (f[0] + f[1])) / pairs : 0;
}

}  // namespace

double sphere_volume_between(double z, double r, double lo, double hi) {
  return std::max(0.0, below(hi - z, r) - below(lo - z, r));
}

double fabric_anisotropy(const ContactSample& sample) {
  int pairs = 0;
  const std::array<double, 3> sums = contact_fabric(sample, &pairs);
  return anisotropy(sums, pairs);
}

Packing measure_packing(const ContactSample& sample, double length, double width, double floor_z,
                        std::span<const double> share) {
  const ParticleSnapshot& snap = sample.beads;
  Packing p;
  p.beads = static_cast<int>(snap.position.size());
  if (p.beads == 0) return p;
  double top = floor_z, d_max = 0;
  for (int i = 0; i < p.beads; ++i) {
    top = std::max(top, snap.position[i][2] + snap.radius[i]);
    d_max = std::max(d_max, 2 * snap.radius[i]);
  }
  const double hi = std::max(floor_z + d_max, top - d_max);
  double solid = 0;
  for (int i = 0; i < p.beads; ++i)
    solid += sphere_volume_between(snap.position[i][2], snap.radius[i], floor_z, hi) *
             (share.empty() ? 1.0 : share[i]);
  p.slab_height = hi - floor_z;
  p.solid_fraction = solid / (length * width * p.slab_height);
  p.void_ratio = 1 / p.solid_fraction - 1;
  int pairs = 0;
  const std::array<double, 3> sums = contact_fabric(sample, &pairs);
  for (int k = 0; k < 3; ++k) p.fabric[k] = pairs > 0 ? sums[k] / pairs : 0;
  p.fabric_anisotropy = anisotropy(sums, pairs);
  int touches = 0;
  for (const ContactForce& c : sample.contacts) touches += c.b < 0 ? 1 : 2;
  p.coordination = double(touches) / p.beads;
  p.bead_coordination = 2.0 * pairs / p.beads;
  return p;
}

}  // namespace simsols
