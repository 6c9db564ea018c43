#include "solver/scene/generators.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "solver/scene/sphere_grid.h"

namespace simsols {
namespace {

// Random insertion gives up after this many attempts per requested sphere.
constexpr std::int64_t kAttemptsPerSphere = 100;
constexpr std::int64_t kExtraAttempts = 10'000;

class Prng {
 public:
  explicit Prng(std::uint64_t seed) : engine_(seed) {}
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform01(); }

 private:
  std::mt19937_64 engine_;
};

struct Box {
  Vec3 lo, hi;
};

// Box of admissible centres for spheres of radius r.
Box shrink(const Vec3& lo, const Vec3& hi, double r) {
  return {{lo[0] + r, lo[1] + r, lo[2] + r}, {hi[0] - r, hi[1] - r, hi[2] - r}};
}

// Sites of a cubic lattice, or of FCC close-packed layers, whose nearest
// neighbours are `spacing` apart, inside `centres`; at most `limit`.
std::vector<Vec3> lattice_sites(const Box& centres, double spacing, bool hexagonal,
                                std::int64_t limit) {
  static const double kLayerOffset[3][2] = {
      {0, 0}, {0.5, std::sqrt(3.0) / 6}, {0, std::sqrt(3.0) / 3}};
  const double s = spacing, eps = 1e-9 * spacing;
  const double dy = hexagonal ? s * std::sqrt(3.0) / 2 : s;
  const double dz = hexagonal ? s * std::sqrt(2.0 / 3.0) : s;
  const Vec3& lo = centres.lo;
  const Vec3& hi = centres.hi;
  std::vector<Vec3> sites;
  for (std::int64_t k = 0; lo[2] + k * dz <= hi[2] + eps; ++k) {
    const double ox = hexagonal ? kLayerOffset[k % 3][0] * s : 0;
    const double oy = hexagonal ? kLayerOffset[k % 3][1] * s : 0;
    for (std::int64_t j = 0; lo[1] + oy + j * dy <= hi[1] + eps; ++j) {
      const double x0 = lo[0] + ox + (hexagonal && j % 2 ? s / 2 : 0);
      for (std::int64_t i = 0; x0 + i * s <= hi[0] + eps; ++i) {
        sites.push_back({x0 + i * s, lo[1] + oy + j * dy, lo[2] + k * dz});
        if (static_cast<std::int64_t>(sites.size()) >= limit) return sites;
      }
    }
  }
  return sites;
}

std::string field_of(size_t g, const char* key) {
  return "generators[" + std::to_string(g) + "]." + key;
}

// Spheres appended to `out` (which holds the particles before them).
class Expansion {
 public:
  explicit Expansion(std::vector<Particle>& out) : out_(out) {}

  std::optional<SceneIssue> lattice(const Generator& g, size_t index) {
    Prng prng(g.seed);
    const std::int64_t limit = g.count > 0 ? g.count : kMaxGenerated + 1;
    const auto sites =
        lattice_sites(shrink(g.min, g.max, g.radius_min), g.spacing, g.hexagonal, limit);
    if (static_cast<std::int64_t>(sites.size()) > kMaxGenerated)
      return SceneIssue{"out_of_range", field_of(index, "max"),
                        "the box holds more than " + std::to_string(kMaxGenerated) +
                            " particles; set count or enlarge spacing"};
    for (Vec3 p : sites) {
      if (g.jitter > 0)
        for (double& x : p) x += prng.uniform(-g.jitter, g.jitter);
      out_.push_back({g.material, g.radius_min, p, g.velocity, {}});
    }
    return std::nullopt;
  }

  // Random sequential insertion, O(1) per attempt with a grid.
  std::optional<SceneIssue> random(const Generator& g, size_t index) {
    Prng prng(g.seed);
    const double r_min = g.radius_min, r_max = g.radius_max;
    double cell = 2 * r_max;
    for (const Particle& p : out_) cell = std::max(cell, 2 * p.radius);
    SphereGrid grid(cell, out_.size() + static_cast<size_t>(g.count));
    for (size_t i = 0; i < out_.size(); ++i) grid.insert(static_cast<int>(i), out_[i].position);
    const std::int64_t budget = kExtraAttempts + kAttemptsPerSphere * g.count;
    std::int64_t attempts = 0;
    for (std::int64_t placed = 0; placed < g.count; ++placed) {
      const double radius = r_min == r_max ? r_min : prng.uniform(r_min, r_max);
      const Box centres = shrink(g.min, g.max, radius);
      Vec3 p{};
      do {
        if (attempts++ == budget)
          return SceneIssue{"out_of_range", field_of(index, "count"),
                            "placed only " + std::to_string(placed) + " of " +
                                std::to_string(g.count) + " non-overlapping spheres in " +
                                std::to_string(budget) + " attempts; lower count or enlarge the box"};
        for (int k = 0; k < 3; ++k) p[k] = prng.uniform(centres.lo[k], centres.hi[k]);
      } while (overlaps_any(grid, p, radius));
      grid.insert(static_cast<int>(out_.size()), p);
      out_.push_back({g.material, radius, p, g.velocity, {}});
    }
    return std::nullopt;
  }

 private:
  bool overlaps_any(const SphereGrid& grid, const Vec3& p, double radius) const {
    bool hit = false;
    grid.for_each_near(p, [&](int j) {
      const Particle& q = out_[j];
      const double dx = p[0] - q.position[0], dy = p[1] - q.position[1], dz = p[2] - q.position[2];
      const double reach = radius + q.radius;
      hit = hit || dx * dx + dy * dy + dz * dz < reach * reach;
    });
    return hit;
  }

  std::vector<Particle>& out_;
};

}  // namespace

double estimated_lattice_sites(const Generator& g) {
  const Box centres = shrink(g.min, g.max, g.radius_min);
  double n = 1;
  for (int k = 0; k < 3; ++k) n *= std::floor((centres.hi[k] - centres.lo[k]) / g.spacing) + 1;
  return n;
}

std::optional<SceneIssue> expand_generators(Scene& scene, std::vector<size_t>* generator_of,
                                            size_t* first) {
  // the clumps' members follow the free spheres the file gives
  const size_t at = scene.clumps.empty() ? scene.particles.size()
                                         : static_cast<size_t>(scene.clumps.front().first);
  std::vector<Particle> spheres(scene.particles.begin(), scene.particles.begin() + at);
  std::vector<size_t> of;
  for (size_t g = 0; g < scene.generators.size(); ++g) {
    Expansion e(spheres);
    const Generator& gen = scene.generators[g];
    auto issue = gen.type == Generator::Type::Lattice ? e.lattice(gen, g) : e.random(gen, g);
    if (issue) return issue;
    of.resize(spheres.size() - at, g);
  }
  const size_t added = spheres.size() - at;
  scene.particles.insert(scene.particles.begin() + at, spheres.begin() + at, spheres.end());
  for (Clump& c : scene.clumps) c.first += static_cast<int>(added);
  scene.generators.clear();
  if (generator_of) *generator_of = std::move(of);
  if (first) *first = at;
  return std::nullopt;
}

}  // namespace simsols
