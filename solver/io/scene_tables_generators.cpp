// [[generators]]: particles placed on a lattice or at random without
// overlap, deterministic on every platform (docs/scene-format.md).
#include <cmath>
#include <numbers>
#include <random>

#include "solver/common/number_text.h"
#include "solver/io/scene_tables.h"
#include "solver/scene/sphere_grid.h"

namespace simsols::scene_toml {
namespace {

// Most particles one generator may create (guards against typos such as a
// box in millimetres with a radius in metres... or the reverse).
constexpr std::int64_t kMaxGenerated = 10'000'000;
// Random insertion gives up after this many attempts per requested sphere.
constexpr std::int64_t kAttemptsPerSphere = 100;
constexpr std::int64_t kExtraAttempts = 10'000;
// Solid fractions: no packing of equal spheres is denser than Kepler's
// pi / (3 sqrt 2); random sequential insertion jams near 0.38 (Torquato &
// Stillinger, Rev. Mod. Phys. 82, 2010): a request above it cannot be met by
// the random generator and is refused before any attempt.
constexpr double kKeplerFraction = 0.7405;
constexpr double kRandomJamFraction = 0.38;

// Deterministic on every platform: mt19937_64 is fully specified, and the
// mapping to [0, 1) is ours (53 high bits).
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

// Box of admissible centres for spheres of radius r; empty when lo > hi.
Box shrink(const Box& b, double r) {
  return {{b.lo[0] + r, b.lo[1] + r, b.lo[2] + r}, {b.hi[0] - r, b.hi[1] - r, b.hi[2] - r}};
}

bool is_empty(const Box& b) { return b.lo[0] > b.hi[0] || b.lo[1] > b.hi[1] || b.lo[2] > b.hi[2]; }

// Sites of a cubic lattice, or of FCC close-packed layers (ABC stacking along
// z), whose nearest neighbours are `spacing` apart, inside `centres`.
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

// Cubic-lattice site count (an FCC lattice has at most ~1.5 times more),
// computed before generating to refuse absurd boxes early.
double estimated_sites(const Box& centres, double spacing) {
  double n = 1;
  for (int k = 0; k < 3; ++k) n *= std::floor((centres.hi[k] - centres.lo[k]) / spacing) + 1;
  return n;
}

// Expands [[generators]] into particles appended to the scene.
class Generators {
 public:
  explicit Generators(Scene& scene) : scene_(scene) {}

  std::vector<size_t> read(const Reader& root) {
    static const std::vector<std::string> kLatticeOnly = {"spacing", "arrangement", "jitter"};
    static const std::vector<std::string> kRandomOnly = {"radius_min", "radius_max"};
    const size_t explicit_particles = scene_.particles.size();
    std::vector<size_t> generator_of;
    const auto tables = root.tables("generators");
    for (size_t g = 0; g < tables.size(); ++g) {
      Reader r(*tables[g], item("generators", g), root.context(),
               {"type", "material", "radius", "radius_min", "radius_max", "min", "max", "spacing",
                "arrangement", "jitter", "seed", "velocity", "count"});
      if (r.choice("type", {"lattice", "random"}) == "lattice") {
        r.forbid(kRandomOnly, "only allowed when type = \"random\"");
        expand_lattice(r);
      } else {
        r.forbid(kLatticeOnly, "only allowed when type = \"lattice\"");
        expand_random(r);
      }
      generator_of.resize(scene_.particles.size() - explicit_particles, g);
    }
    return generator_of;
  }

 private:
  // Fields shared by both generator types.
  struct Common {
    int material;
    Box box;
    Vec3 velocity;
    Prng prng;
  };

  Common read_common(const Reader& r) {
    const int material = r.material("material", scene_);
    const Box box{r.vec3("min"), r.vec3("max")};
    for (int k = 0; k < 3; ++k)
      if (box.hi[k] < box.lo[k])
        r.fail("out_of_range", "max",
               "max must be >= min on every axis (axis " + std::to_string(k) + ": " +
                   num(box.hi[k]) + " < " + num(box.lo[k]) + ")");
    const std::int64_t seed = r.optional_integer("seed").value_or(1);
    if (seed < 0)
      r.fail("out_of_range", "seed", std::to_string(seed) + " is out of range, allowed [0, 2^63)");
    return {material, box, r.vec3("velocity", {}), Prng(static_cast<std::uint64_t>(seed))};
  }

  double positive(const Reader& r, std::string_view key) {
    const double v = r.number(key);
    r.check_range(key, v, v > 0, "(0, inf)");
    return v;
  }

  std::int64_t count_limit(const Reader& r, bool required) {
    const std::optional<std::int64_t> count =
        required ? r.integer("count") : r.optional_integer("count");
    if (!count) return kMaxGenerated + 1;
    if (*count < 1 || *count > kMaxGenerated)
      r.fail("out_of_range", "count",
             std::to_string(*count) + " is out of range, allowed [1, " +
                 std::to_string(kMaxGenerated) + "]");
    return *count;
  }

  void add_particle(const Common& c, double radius, const Vec3& position) {
    scene_.particles.push_back({c.material, radius, position, c.velocity, {}});
  }

  void expand_lattice(const Reader& r) {
    Common c = read_common(r);
    const double radius = positive(r, "radius");
    const double spacing = r.number("spacing", 2 * radius);
    r.check_range("spacing", spacing, spacing >= 2 * radius * 0.99,
                  "[" + num(2 * radius * 0.99) + ", inf) (0.99 x diameter)");
    const bool hexagonal = r.choice("arrangement", "cubic", {"cubic", "hexagonal"}) == "hexagonal";
    const double jitter = r.number("jitter", 0);
    r.check_range("jitter", jitter, jitter >= 0 && jitter < spacing / 2,
                  "[0, " + num(spacing / 2) + ") (spacing / 2)");
    const std::int64_t limit = count_limit(r, false);
    const Box centres = shrink(c.box, radius);
    if (is_empty(centres))
      r.fail("out_of_range", "max",
             "the box [min, max] cannot hold one sphere of radius " + num(radius));
    const std::string too_many = "the box holds more than " + std::to_string(kMaxGenerated) +
                                 " particles; set count or enlarge spacing";
    if (limit > kMaxGenerated && estimated_sites(centres, spacing) > 2.0 * kMaxGenerated)
      r.fail("out_of_range", "max", too_many);
    const auto sites = lattice_sites(centres, spacing, hexagonal, limit);
    if (static_cast<std::int64_t>(sites.size()) > kMaxGenerated)
      r.fail("out_of_range", "max", too_many);
    for (Vec3 p : sites) {
      if (jitter > 0)
        for (double& x : p) x += c.prng.uniform(-jitter, jitter);
      add_particle(c, radius, p);
    }
  }

  std::pair<double, double> read_radius_range(const Reader& r) {
    if (r.has("radius")) {
      if (r.has("radius_min") || r.has("radius_max"))
        r.fail("conflicting_keys", "radius",
               "give either radius or radius_min and radius_max, not both");
      const double radius = positive(r, "radius");
      return {radius, radius};
    }
    if (!r.has("radius_min") && !r.has("radius_max"))
      r.fail("missing_field", "radius",
             "required field 'radius' (or radius_min and radius_max) is missing");
    const double lo = positive(r, "radius_min");
    const double hi = r.number("radius_max");
    r.check_range("radius_max", hi, hi >= lo, "[" + num(lo) + ", inf) (>= radius_min)");
    return {lo, hi};
  }

  // Random sequential insertion of non-overlapping spheres (also clear of
  // the particles already in the scene), O(1) per attempt with a grid.
  void expand_random(const Reader& r) {
    Common c = read_common(r);
    const auto [r_min, r_max] = read_radius_range(r);
    const std::int64_t count = count_limit(r, true);
    if (is_empty(shrink(c.box, r_max)))
      r.fail("out_of_range", "max",
             "the box [min, max] cannot hold one sphere of radius " + num(r_max));
    {  // at once, not after the attempt budget: the solid volume asked for
      double volume = 1;
      for (int k = 0; k < 3; ++k) volume *= c.box.hi[k] - c.box.lo[k];
      const double solid = double(count) * 4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min;
      const double limit =
          kRandomJamFraction * volume / (4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min);
      if (solid > kRandomJamFraction * volume)
        r.fail("out_of_range", "count",
               std::to_string(count) + " spheres of radius >= " + num(r_min) + " fill " +
                   shortest_number(std::round(solid / volume * 1000) / 1000) +
                   " of the box [min, max] (" +
                   (solid > kKeplerFraction * volume ? "no packing holds more than 0.7405"
                                                     : "random insertion jams near 0.38") +
                   "); allowed [1, " + std::to_string(static_cast<std::int64_t>(limit)) +
                   "] here: lower count, enlarge the box, or use a lattice generator");
    }
    double cell = 2 * r_max;
    for (const Particle& p : scene_.particles) cell = std::max(cell, 2 * p.radius);
    SphereGrid grid(cell, scene_.particles.size() + static_cast<size_t>(count));
    for (size_t i = 0; i < scene_.particles.size(); ++i)
      grid.insert(static_cast<int>(i), scene_.particles[i].position);
    const std::int64_t budget = kExtraAttempts + kAttemptsPerSphere * count;
    std::int64_t attempts = 0;
    for (std::int64_t placed = 0; placed < count; ++placed) {
      const double radius = r_min == r_max ? r_min : c.prng.uniform(r_min, r_max);
      const Box centres = shrink(c.box, radius);
      Vec3 p{};
      do {
        if (attempts++ == budget)
          r.fail("out_of_range", "count",
                 "placed only " + std::to_string(placed) + " of " + std::to_string(count) +
                     " non-overlapping spheres in " + std::to_string(budget) +
                     " attempts; lower count or enlarge the box");
        for (int k = 0; k < 3; ++k) p[k] = c.prng.uniform(centres.lo[k], centres.hi[k]);
      } while (overlaps_any(grid, p, radius));
      grid.insert(static_cast<int>(scene_.particles.size()), p);
      add_particle(c, radius, p);
    }
  }

  bool overlaps_any(const SphereGrid& grid, const Vec3& p, double radius) const {
    bool hit = false;
    grid.for_each_near(p, [&](int j) {
      const Particle& q = scene_.particles[j];
      const double dx = p[0] - q.position[0], dy = p[1] - q.position[1], dz = p[2] - q.position[2];
      const double reach = radius + q.radius;
      hit = hit || dx * dx + dy * dy + dz * dz < reach * reach;
    });
    return hit;
  }

  Scene& scene_;
};

}  // namespace

std::vector<size_t> read_generators(const Reader& root, Scene& scene) {
  return Generators(scene).read(root);
}

}  // namespace simsols::scene_toml
