// [[generators]]: read into Scene::generators, checked as far as reading
// can (the box, the radii, the solid fraction asked for); the spheres are
// placed by place_scene (solver/scene/generators.h) (docs/scene-format.md).
#include <cmath>
#include <numbers>

#include "solver/common/number_text.h"
#include "solver/io/scene_tables.h"
#include "solver/scene/generators.h"

namespace simsols::scene_toml {
namespace {

// Solid fractions: no packing of equal spheres is denser than Kepler's
// pi / (3 sqrt 2); random sequential insertion jams near 0.38 (Torquato &
// Stillinger, Rev. Mod. Phys. 82, 2010): a request above it cannot be met by
// the random generator and is refused before any attempt.
constexpr double kKeplerFraction = 0.7405;
constexpr double kRandomJamFraction = 0.38;

bool cannot_hold(const Generator& g, double r) {
  for (int k = 0; k < 3; ++k)
    if (g.min[k] + r > g.max[k] - r) return true;
  return false;
}

// Reads [[generators]] into descriptions.
class Generators {
 public:
  explicit Generators(Scene& scene) : scene_(scene) {}

  void read(const Reader& root) {
    static const std::vector<std::string> kLatticeOnly = {"spacing", "arrangement", "jitter"};
    static const std::vector<std::string> kRandomOnly = {"radius_min", "radius_max"};
    const auto tables = root.tables("generators");
    for (size_t g = 0; g < tables.size(); ++g) {
      Reader r(*tables[g], item("generators", g), root.context(),
               {"type", "material", "radius", "radius_min", "radius_max", "min", "max", "spacing",
                "arrangement", "jitter", "seed", "velocity", "count"});
      if (r.choice("type", {"lattice", "random"}) == "lattice") {
        r.forbid(kRandomOnly, "only allowed when type = \"random\"");
        scene_.generators.push_back(read_lattice(r));
      } else {
        r.forbid(kLatticeOnly, "only allowed when type = \"lattice\"");
        scene_.generators.push_back(read_random(r));
      }
    }
  }

 private:
  // Fields shared by both generator types.
  Generator read_common(const Reader& r, Generator::Type type) {
    Generator g;
    g.type = type;
    g.material = r.material("material", scene_);
    g.min = r.vec3("min");
    g.max = r.vec3("max");
    for (int k = 0; k < 3; ++k)
      if (g.max[k] < g.min[k])
        r.fail("out_of_range", "max",
               "max must be >= min on every axis (axis " + std::to_string(k) + ": " +
                   num(g.max[k]) + " < " + num(g.min[k]) + ")");
    const std::int64_t seed = r.optional_integer("seed").value_or(1);
    if (seed < 0)
      r.fail("out_of_range", "seed", std::to_string(seed) + " is out of range, allowed [0, 2^63)");
    g.seed = static_cast<std::uint64_t>(seed);
    g.velocity = r.vec3("velocity", {});
    return g;
  }

  double positive(const Reader& r, std::string_view key) {
    const double v = r.number(key);
    r.check_range(key, v, v > 0, "(0, inf)");
    return v;
  }

  // The count asked for; 0 when an optional one is absent.
  std::int64_t read_count(const Reader& r, bool required) {
    const std::optional<std::int64_t> count =
        required ? r.integer("count") : r.optional_integer("count");
    if (!count) return 0;
    if (*count < 1 || *count > kMaxGenerated)
      r.fail("out_of_range", "count",
             std::to_string(*count) + " is out of range, allowed [1, " +
                 std::to_string(kMaxGenerated) + "]");
    return *count;
  }

  Generator read_lattice(const Reader& r) {
    Generator g = read_common(r, Generator::Type::Lattice);
    g.radius_min = g.radius_max = positive(r, "radius");
    g.spacing = r.number("spacing", 2 * g.radius_min);
    r.check_range("spacing", g.spacing, g.spacing >= 2 * g.radius_min * 0.99,
                  "[" + num(2 * g.radius_min * 0.99) + ", inf) (0.99 x diameter)");
    g.hexagonal = r.choice("arrangement", "cubic", {"cubic", "hexagonal"}) == "hexagonal";
    g.jitter = r.number("jitter", 0);
    r.check_range("jitter", g.jitter, g.jitter >= 0 && g.jitter < g.spacing / 2,
                  "[0, " + num(g.spacing / 2) + ") (spacing / 2)");
    g.count = read_count(r, false);
    if (cannot_hold(g, g.radius_min))
      r.fail("out_of_range", "max",
             "the box [min, max] cannot hold one sphere of radius " + num(g.radius_min));
    if (g.count == 0 && estimated_lattice_sites(g) > 2.0 * kMaxGenerated)
      r.fail("out_of_range", "max",
             "the box holds more than " + std::to_string(kMaxGenerated) +
                 " particles; set count or enlarge spacing");
    return g;
  }

  void read_radius_range(const Reader& r, Generator& g) {
    if (r.has("radius")) {
      if (r.has("radius_min") || r.has("radius_max"))
        r.fail("conflicting_keys", "radius",
               "give either radius or radius_min and radius_max, not both");
      g.radius_min = g.radius_max = positive(r, "radius");
      return;
    }
    if (!r.has("radius_min") && !r.has("radius_max"))
      r.fail("missing_field", "radius",
             "required field 'radius' (or radius_min and radius_max) is missing");
    g.radius_min = positive(r, "radius_min");
    g.radius_max = r.number("radius_max");
    r.check_range("radius_max", g.radius_max, g.radius_max >= g.radius_min,
                  "[" + num(g.radius_min) + ", inf) (>= radius_min)");
  }

  Generator read_random(const Reader& r) {
    Generator g = read_common(r, Generator::Type::Random);
    read_radius_range(r, g);
    g.count = read_count(r, true);
    if (cannot_hold(g, g.radius_max))
      r.fail("out_of_range", "max",
             "the box [min, max] cannot hold one sphere of radius " + num(g.radius_max));
    check_fraction(r, g);
    return g;
  }

  // At once, not after the attempt budget: the solid volume asked for.
  void check_fraction(const Reader& r, const Generator& g) {
    double volume = 1;
    for (int k = 0; k < 3; ++k) volume *= g.max[k] - g.min[k];
    const double r3 = g.radius_min * g.radius_min * g.radius_min;
    const double solid = double(g.count) * 4.0 / 3.0 * std::numbers::pi * r3;
    if (solid <= kRandomJamFraction * volume) return;
    const double limit = kRandomJamFraction * volume / (4.0 / 3.0 * std::numbers::pi * r3);
    r.fail("out_of_range", "count",
           std::to_string(g.count) + " spheres of radius >= " + num(g.radius_min) + " fill " +
               shortest_number(std::round(solid / volume * 1000) / 1000) +
               " of the box [min, max] (" +
               (solid > kKeplerFraction * volume ? "no packing holds more than 0.7405"
                                                 : "random insertion jams near 0.38") +
               "); allowed [1, " + std::to_string(static_cast<std::int64_t>(limit)) +
               "] here: lower count, enlarge the box, or use a lattice generator");
  }

  Scene& scene_;
};

}  // namespace

void read_generators(const Reader& root, Scene& scene) { Generators(scene).read(root); }

}  // namespace simsols::scene_toml
