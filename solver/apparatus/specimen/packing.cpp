#include "solver/apparatus/specimen/packing.h"

#include <algorithm>
#include <cmath>
#include <utility>

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

// Each bead's grain: the map's, or the bead itself.
std::vector<int> grain_ids(const GrainMap& grains, int beads) {
  if (!grains.grain.empty()) return grains.grain;
  std::vector<int> g(beads);
  for (int i = 0; i < beads; ++i) g[i] = i;
  return g;
}

// The largest grain's diameter: twice the farthest reach of its members
// from their mean centre.
double largest_grain(const ParticleSnapshot& snap, const std::vector<int>& grain, int grains) {
  std::vector<Vec3> centre(grains, Vec3{});
  std::vector<int> members(grains, 0);
  for (size_t i = 0; i < grain.size(); ++i) {
    for (int k = 0; k < 3; ++k) centre[grain[i]][k] += snap.position[i][k];
    ++members[grain[i]];
  }
  for (int g = 0; g < grains; ++g)
    for (int k = 0; k < 3; ++k) centre[g][k] /= std::max(1, members[g]);
  double reach = 0;
  for (size_t i = 0; i < grain.size(); ++i) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(snap.position[i][k] - centre[grain[i]][k], 2);
    reach = std::max(reach, std::sqrt(d2) + snap.radius[i]);
  }
  return 2 * reach;
}

// Distinct grain-grain and grain-wall contacts: several member contacts
// between the same two bodies are one.
struct Touches {
  long grain_pairs = 0, wall_pairs = 0;
};

Touches count_touches(const std::vector<ContactForce>& contacts, const std::vector<int>& grain) {
  std::vector<std::pair<int, int>> pairs, walls;
  for (const ContactForce& c : contacts) {
    const int a = grain[c.a];
    if (c.b < 0) {
      walls.emplace_back(a, c.b);
    } else if (grain[c.b] != a) {
      pairs.emplace_back(std::min(a, grain[c.b]), std::max(a, grain[c.b]));
    }
  }
  const auto distinct = [](std::vector<std::pair<int, int>>& v) {
    std::sort(v.begin(), v.end());
    return static_cast<long>(std::unique(v.begin(), v.end()) - v.begin());
  };
  return {distinct(pairs), distinct(walls)};
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
                        const GrainMap& grains) {
  const ParticleSnapshot& snap = sample.beads;
  Packing p;
  p.beads = static_cast<int>(snap.position.size());
  if (p.beads == 0) return p;
  const auto share = [&](int i) { return grains.share.empty() ? 1.0 : grains.share[i]; };
  const std::vector<int> grain = grain_ids(grains, p.beads);
  p.grains = grain.empty() ? 0 : *std::max_element(grain.begin(), grain.end()) + 1;
  double top = floor_z, total = 0;
  for (int i = 0; i < p.beads; ++i) {
    top = std::max(top, snap.position[i][2] + snap.radius[i]);
    total += 4.0 / 3.0 * kPi * std::pow(snap.radius[i], 3) * share(i);
  }
  p.height = top - floor_z;
  p.bulk_void_ratio = p.height > 0 ? length * width * p.height / total - 1 : 0;
  const double d_max = largest_grain(snap, grain, p.grains);
  const double hi = std::max(floor_z + d_max, top - d_max);
  double solid = 0;
  for (int i = 0; i < p.beads; ++i)
    solid += sphere_volume_between(snap.position[i][2], snap.radius[i], floor_z, hi) * share(i);
  p.slab_height = hi - floor_z;
  p.solid_fraction = solid / (length * width * p.slab_height);
  p.void_ratio = 1 / p.solid_fraction - 1;
  int pairs = 0;
  const std::array<double, 3> sums = contact_fabric(sample, &pairs);
  for (int k = 0; k < 3; ++k) p.fabric[k] = pairs > 0 ? sums[k] / pairs : 0;
  p.fabric_anisotropy = anisotropy(sums, pairs);
  const Touches t = count_touches(sample.contacts, grain);
  p.coordination = double(2 * t.grain_pairs + t.wall_pairs) / p.grains;
  p.grain_coordination = 2.0 * t.grain_pairs / p.grains;
  return p;
}

}  // namespace simsols
