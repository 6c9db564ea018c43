// TOML scene files: loader, particle generators and writer. See scene_toml.h
// for the design and docs/scene-format.md for the format.
#include "solver/io/scene_toml.h"

#include "solver/common/input_file.h"
#include "solver/common/number_text.h"
#include "solver/scene/sphere_grid.h"
#include "solver/apparatus/shear_box.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <utility>

#include "solver/common/did_you_mean.h"
#include "solver/common/errors.h"

namespace simsols {
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

// ---------------------------------------------------------------------------
// Small text helpers.

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string item(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

std::string num(double v) { return shortest_number(v); }

std::string join(const std::vector<std::string>& words, bool quoted) {
  std::string out;
  for (const std::string& w : words) {
    if (!out.empty()) out += ", ";
    out += quoted ? "\"" + w + "\"" : w;
  }
  return out;
}

const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

int line_of(const toml::source_region& r) { return static_cast<int>(r.begin.line); }

// Divides by the length unless the vector is zero or already unit (so a
// written and re-read unit vector keeps its exact bits).
Vec3 normalized(const Vec3& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n == 0 || !std::isfinite(n) || std::abs(n - 1) <= 4 * std::numeric_limits<double>::epsilon())
    return v;
  return {v[0] / n, v[1] / n, v[2] / n};
}

// ---------------------------------------------------------------------------
// Reader: typed access to one TOML table, with its dotted path.

// What every Reader needs besides its table: the file, and the problems
// that let the reading go on (unknown keys), reported together with the
// first one that stops it, or at the end.
struct Context {
  std::string file;
  std::vector<SceneProblem> found;

  void note(const std::string& code, int line, const std::string& field,
            const std::string& message) {
    found.push_back({code, line, field, message});
  }
  [[noreturn]] void fail(const std::string& code, int line, const std::string& field,
                         const std::string& message) {
    note(code, line, field, message);
    throw SceneError(file, found);
  }
  void throw_if_any() const {
    if (!found.empty()) throw SceneError(file, found);
  }
};

class Reader {
 public:
  // Notes every key outside `allowed` (unknown_key); the reading goes on.
  Reader(const toml::table& table, std::string path, Context& ctx, std::vector<std::string> allowed)
      : table_(table), path_(std::move(path)), ctx_(ctx), allowed_(std::move(allowed)) {
    for (auto&& [key, node] : table_) {
      if (std::find(allowed_.begin(), allowed_.end(), key.str()) != allowed_.end()) continue;
      ctx_.note("unknown_key", line_of(key.source()), child(path_, key.str()),
                "unknown key '" + std::string(key.str()) + "'" +
                    did_you_mean(key.str(), allowed_) +
                    "; allowed keys: " + join(allowed_, false));
    }
  }

  std::string field(std::string_view key) const { return child(path_, key); }
  bool has(std::string_view key) const { return table_.contains(key); }
  bool is_boolean(std::string_view key) const {
    const toml::node* n = get(key);
    return n && n->is_boolean();
  }

  [[noreturn]] void fail(const std::string& code, std::string_view key,
                         const std::string& message) const {
    const toml::node* n = table_.get(key);
    ctx_.fail(code, line_of(n ? n->source() : table_.source()), field(key), message);
  }

  void check_range(std::string_view key, double v, bool ok, const std::string& allowed) const {
    if (!ok) fail("out_of_range", key, num(v) + " is out of range, allowed " + allowed);
  }

  // Keys allowed by the table kind but not by its `type` (noted, as unknown keys).
  void forbid(const std::vector<std::string>& keys, const std::string& reason) const {
    for (const std::string& k : keys)
      if (has(k))
        ctx_.note("unknown_key", line_of(table_.get(k)->source()), field(k),
                  "unknown key '" + k + "': " + reason);
  }

  double number(std::string_view key) const { return to_number(key, require(key)); }
  double number(std::string_view key, double fallback) const {
    const toml::node* n = get(key);
    return n ? to_number(key, *n) : fallback;
  }
  std::optional<double> optional_number(std::string_view key) const {
    const toml::node* n = get(key);
    return n ? std::optional<double>(to_number(key, *n)) : std::nullopt;
  }

  std::optional<std::int64_t> optional_integer(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_integer())
      fail("wrong_type", key, std::string("expected an integer, got ") + type_name(*n));
    return n->as_integer()->get();
  }
  std::int64_t integer(std::string_view key) const {
    require(key);
    return *optional_integer(key);
  }

  bool boolean(std::string_view key, bool fallback) const {
    const toml::node* n = get(key);
    if (!n) return fallback;
    if (!n->is_boolean())
      fail("wrong_type", key, std::string("expected a boolean, got ") + type_name(*n));
    return n->as_boolean()->get();
  }

  std::string string(std::string_view key) const { return to_string(key, require(key)); }
  std::string string(std::string_view key, const std::string& fallback) const {
    const toml::node* n = get(key);
    return n ? to_string(key, *n) : fallback;
  }

  // A string that must be one of `values` (bad_enum otherwise).
  std::string choice(std::string_view key, const std::vector<std::string>& values) const {
    return checked_choice(key, string(key), values);
  }
  std::string choice(std::string_view key, const std::string& fallback,
                     const std::vector<std::string>& values) const {
    return checked_choice(key, string(key, fallback), values);
  }

  Vec3 vec3(std::string_view key) const { return to_vec3(key, require(key)); }
  Vec3 vec3(std::string_view key, const Vec3& fallback) const {
    const toml::node* n = get(key);
    return n ? to_vec3(key, *n) : fallback;
  }

  // Index of the material named by the string at `key`.
  int material(std::string_view key, const Scene& scene) const {
    return material_index(key, string(key), scene);
  }

  // Exactly two material names, e.g. materials = ["glass", "steel"].
  std::pair<int, int> material_pair(std::string_view key, const Scene& scene) const {
    const toml::array* a = as_array(key, require(key));
    if (a->size() != 2)
      fail("bad_vector", key,
           "has " + std::to_string(a->size()) + " elements, expected 2 material names");
    return {material_index(key, to_string(key, *a->get(0)), scene),
            material_index(key, to_string(key, *a->get(1)), scene)};
  }

  // The sub-table at `key`; an empty table when absent.
  const toml::table& table(std::string_view key) const {
    static const toml::table kEmpty;
    const toml::node* n = get(key);
    if (!n) return kEmpty;
    if (!n->is_table())
      fail("wrong_type", key,
           std::string("expected a table [") + std::string(key) + "], got " + type_name(*n));
    return *n->as_table();
  }

  // The tables of an array of tables ([[key]] or key = [{...}]); empty when absent.
  std::vector<const toml::table*> tables(std::string_view key) const {
    std::vector<const toml::table*> out;
    const toml::node* n = get(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a)
      fail("wrong_type", key,
           "expected an array of tables [[" + std::string(key) + "]], got " + type_name(*n));
    for (size_t i = 0; i < a->size(); ++i) {
      const toml::node& e = *a->get(i);
      if (!e.is_table())
        ctx_.fail("wrong_type", line_of(e.source()), item(field(key), i),
                  std::string("expected a table, got ") + type_name(e));
      out.push_back(e.as_table());
    }
    return out;
  }

 private:
  std::string checked_choice(std::string_view key, const std::string& v,
                             const std::vector<std::string>& values) const {
    if (std::find(values.begin(), values.end(), v) == values.end())
      fail("bad_enum", key, "'" + v + "' is not allowed; allowed values: " + join(values, true));
    return v;
  }
  const toml::node* get(std::string_view key) const { return table_.get(key); }

  const toml::node& require(std::string_view key) const {
    const toml::node* n = get(key);
    if (!n) fail("missing_field", key, "required field '" + std::string(key) + "' is missing");
    return *n;
  }

  double to_number(std::string_view key, const toml::node& n) const {
    if (n.is_integer()) return static_cast<double>(n.as_integer()->get());
    if (!n.is_floating_point())
      fail("wrong_type", key, std::string("expected a number, got ") + type_name(n));
    const double v = n.as_floating_point()->get();
    if (!std::isfinite(v)) fail("not_finite", key, num(v) + " is not a finite number");
    return v;
  }

  std::string to_string(std::string_view key, const toml::node& n) const {
    if (!n.is_string())
      fail("wrong_type", key, std::string("expected a string, got ") + type_name(n));
    return n.as_string()->get();
  }

  const toml::array* as_array(std::string_view key, const toml::node& n) const {
    if (!n.is_array())
      fail("wrong_type", key, std::string("expected an array, got ") + type_name(n));
    return n.as_array();
  }

  Vec3 to_vec3(std::string_view key, const toml::node& n) const {
    const toml::array* a = as_array(key, n);
    if (a->size() != 3)
      fail("bad_vector", key,
           "has " + std::to_string(a->size()) + " elements, expected 3 numbers [x, y, z]");
    Vec3 v{};
    for (size_t k = 0; k < 3; ++k) {
      const toml::node& e = *a->get(k);
      if (e.is_integer()) {
        v[k] = static_cast<double>(e.as_integer()->get());
      } else if (e.is_floating_point()) {
        v[k] = e.as_floating_point()->get();
        if (!std::isfinite(v[k]))
          fail("not_finite", key,
               "component " + std::to_string(k) + " is " + num(v[k]) + ", not a finite number");
      } else {
        fail("bad_vector", key,
             "component " + std::to_string(k) + " is " + type_name(e) + ", expected a number");
      }
    }
    return v;
  }

  int material_index(std::string_view key, const std::string& name, const Scene& scene) const {
    const int i = scene.material_index(name);
    if (i >= 0) return i;
    std::vector<std::string> names;
    for (const Material& m : scene.materials) names.push_back(m.name);
    fail("unknown_material", key,
         "material '" + name + "' is not defined; defined materials: " +
             (names.empty() ? std::string("none") : join(names, true)));
  }

  const toml::table& table_;
  std::string path_;
  Context& ctx_;
  std::vector<std::string> allowed_;
};

// ---------------------------------------------------------------------------
// Generators.

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

// ---------------------------------------------------------------------------
// Loader: reads one document into a Scene.

class Loader {
 public:
  explicit Loader(const std::string& file) { ctx_.file = file; }

  Scene load(const toml::table& root) {
    root_ = &root;
    Reader r(root, "", ctx_,
             {"scene", "materials", "interactions", "particles", "generators", "walls", "effects",
              "numerics", "output", "shear_box", "view"});
    read_info(r);
    read_materials(r);
    read_interactions(r);
    read_particles(r);
    read_generators(r);
    read_walls(r);
    read_shear_box(r);
    read_effects(r);
    read_numerics(r);
    read_outputs(r);
    read_view(r);
    for (SceneIssue& issue : find_scene_issues(scene_)) note(std::move(issue));
    ctx_.throw_if_any();
    return std::move(scene_);
  }

 private:
  void read_info(const Reader& root) {
    Reader r(root.table("scene"), "scene", ctx_, {"name", "description"});
    scene_.name = r.string("name", scene_.name);
    scene_.description = r.string("description", "");
  }

  void read_materials(const Reader& root) {
    const auto tables = root.tables("materials");
    for (size_t i = 0; i < tables.size(); ++i) {
      Reader r(*tables[i], item("materials", i), ctx_,
               {"name", "young_modulus", "poisson_ratio", "density", "restitution",
                "sliding_friction", "rolling_friction"});
      Material m;
      m.name = r.string("name");
      m.young_modulus = r.number("young_modulus");
      m.poisson_ratio = r.number("poisson_ratio");
      m.density = r.number("density");
      m.restitution = r.number("restitution");
      m.sliding_friction = r.number("sliding_friction", 0);
      m.rolling_friction = r.number("rolling_friction", 0);
      scene_.materials.push_back(m);
    }
  }

  void read_interactions(const Reader& root) {
    const auto tables = root.tables("interactions");
    for (size_t i = 0; i < tables.size(); ++i) {
      Reader r(*tables[i], item("interactions", i), ctx_,
               {"materials", "restitution", "sliding_friction", "rolling_friction",
                "liquid_volume", "contact_angle"});
      PairOverride o;
      std::tie(o.material_a, o.material_b) = r.material_pair("materials", scene_);
      o.restitution = r.optional_number("restitution");
      o.sliding_friction = r.optional_number("sliding_friction");
      o.rolling_friction = r.optional_number("rolling_friction");
      o.liquid_volume = r.optional_number("liquid_volume");
      o.contact_angle = r.optional_number("contact_angle");
      scene_.pair_overrides.push_back(o);
    }
  }

  void read_particles(const Reader& root) {
    const auto tables = root.tables("particles");
    for (size_t i = 0; i < tables.size(); ++i) {
      Reader r(*tables[i], item("particles", i), ctx_,
               {"material", "radius", "position", "velocity", "angular_velocity"});
      Particle p;
      p.material = r.material("material", scene_);
      p.radius = r.number("radius");
      p.position = r.vec3("position");
      p.velocity = r.vec3("velocity", {});
      p.angular_velocity = r.vec3("angular_velocity", {});
      scene_.particles.push_back(p);
    }
    explicit_particles_ = scene_.particles.size();
  }

  void read_generators(const Reader& root) {
    static const std::vector<std::string> kLatticeOnly = {"spacing", "arrangement", "jitter"};
    static const std::vector<std::string> kRandomOnly = {"radius_min", "radius_max"};
    const auto tables = root.tables("generators");
    for (size_t g = 0; g < tables.size(); ++g) {
      Reader r(*tables[g], item("generators", g), ctx_,
               {"type", "material", "radius", "radius_min", "radius_max", "min", "max", "spacing",
                "arrangement", "jitter", "seed", "velocity", "count"});
      if (r.choice("type", {"lattice", "random"}) == "lattice") {
        r.forbid(kRandomOnly, "only allowed when type = \"random\"");
        expand_lattice(r);
      } else {
        r.forbid(kLatticeOnly, "only allowed when type = \"lattice\"");
        expand_random(r);
      }
      generator_of_.resize(scene_.particles.size() - explicit_particles_, g);
    }
  }

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
      const double limit = kRandomJamFraction * volume /
                           (4.0 / 3.0 * std::numbers::pi * r_min * r_min * r_min);
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

  void read_walls(const Reader& root) {
    const auto tables = root.tables("walls");
    for (size_t i = 0; i < tables.size(); ++i) {
      Reader r(*tables[i], item("walls", i), ctx_,
               {"name", "type", "material", "point", "normal", "axis_u", "half_u", "half_v",
                "velocity", "servo"});
      Wall w;
      w.name = r.string("name", "wall" + std::to_string(i));
      const bool rectangle = r.choice("type", "plane", {"plane", "rectangle"}) == "rectangle";
      if (!rectangle)
        r.forbid({"axis_u", "half_u", "half_v"}, "only allowed when type = \"rectangle\"");
      w.material = r.material("material", scene_);
      w.point = r.vec3("point");
      w.normal = normalized(r.vec3("normal"));
      w.velocity = r.vec3("velocity", {});
      if (r.has("servo")) {
        Reader sv(r.table("servo"), r.field("servo"), ctx_,
                  {"target_force", "gain", "max_speed", "integral_time", "mass"});
        w.servo.enabled = true;
        w.servo.target_force = sv.number("target_force");
        w.servo.mass = sv.number("mass", 0);
        if (w.servo.mass > 0) {
          sv.forbid({"gain", "max_speed", "integral_time"},
                    "a dead-weight wall (mass > 0) has no servo settings");
        } else {
          w.servo.gain = sv.number("gain");
          w.servo.max_speed = sv.number("max_speed");
          w.servo.integral_time = sv.number("integral_time", 0);
        }
      }
      if (rectangle) {
        w.shape = WallShape::Rectangle;
        w.axis_u = normalized(r.vec3("axis_u"));
        w.half_u = r.number("half_u");
        w.half_v = r.number("half_v");
      }
      scene_.walls.push_back(w);
    }
  }

  void read_shear_box(const Reader& root) {
    if (!root.has("shear_box")) return;
    Reader r(root.table("shear_box"), "shear_box", ctx_,
             {"length", "width", "split_height", "gap", "wall_material", "normal_stress",
              "shear_speed", "inertial_number", "shear_displacement", "loading",
              "platen_mass", "servo_gain",
              "servo_max_speed", "servo_integral_time", "settle_time", "consolidate_time", "rows",
              "specimen"});
    ShearBox b;
    b.length = r.number("length", b.length);
    b.width = r.number("width", b.width);
    b.split_height = r.number("split_height", b.split_height);
    b.gap = r.number("gap", b.gap);
    if (r.has("wall_material")) {
      const std::string name = r.string("wall_material");
      // "steel" is built in (default_box_steel) unless the scene defines it
      if (name != "steel" || scene_.material_index(name) >= 0)
        b.wall_material = r.material("wall_material", scene_);
    }
    b.normal_stress = r.number("normal_stress", b.normal_stress);
    b.shear_speed = r.number("shear_speed", b.shear_speed);
    b.inertial_number = r.number("inertial_number", b.inertial_number);
    b.shear_displacement = r.number("shear_displacement", b.shear_displacement);
    b.loading = r.choice("loading", "dead_weight", {"dead_weight", "servo"}) == "servo"
                    ? ShearBox::Loading::Servo
                    : ShearBox::Loading::DeadWeight;
    b.platen_mass = r.number("platen_mass", b.platen_mass);
    b.servo_gain = r.number("servo_gain", b.servo_gain);
    b.servo_max_speed = r.number("servo_max_speed", b.servo_max_speed);
    b.servo_integral_time = r.number("servo_integral_time", b.servo_integral_time);
    b.settle_time = r.number("settle_time", b.settle_time);
    b.consolidate_time = r.number("consolidate_time", b.consolidate_time);
    const std::int64_t rows = r.optional_integer("rows").value_or(b.rows);
    if (rows < 10 || rows > 1000000)
      r.fail("out_of_range", "rows", std::to_string(rows) + " is out of range, allowed [10, 1000000]");
    b.rows = static_cast<int>(rows);

    Reader sp(r.table("specimen"), "shear_box.specimen", ctx_,
              {"method", "material", "diameter", "layers", "clearance", "seed"});
    ShearSpecimen& s = b.specimen;
    const std::string method = sp.choice("method", "layers", {"layers", "pour", "given"});
    s.method = method == "layers" ? ShearSpecimen::Method::Layers
               : method == "pour" ? ShearSpecimen::Method::Pour
                                  : ShearSpecimen::Method::Given;
    if (s.method == ShearSpecimen::Method::Given) {
      sp.forbid({"material", "diameter", "layers", "clearance", "seed"},
                "only allowed when method = \"layers\" or \"pour\"");
    } else {
      s.material = sp.material("material", scene_);
      s.diameter = sp.number("diameter");
      const std::int64_t layers = sp.integer("layers");
      if (layers < 1 || layers > 200)
        sp.fail("out_of_range", "layers", std::to_string(layers) + " is out of range, allowed [1, 200]");
      s.layers = static_cast<int>(layers);
      if (s.method == ShearSpecimen::Method::Pour)
        sp.forbid({"clearance"}, "only allowed when method = \"layers\"");
      s.clearance = sp.choice("clearance", "shift", {"shift", "spread"}) == "shift"
                        ? ShearSpecimen::Clearance::Shift
                        : ShearSpecimen::Clearance::Spread;
      const std::int64_t seed = sp.optional_integer("seed").value_or(1);
      if (seed < 0)
        sp.fail("out_of_range", "seed", std::to_string(seed) + " is out of range, allowed [0, 2^63)");
      s.seed = seed;
    }
    scene_.shear_box = b;
    if (auto issue = build_shear_box(scene_)) fail(std::move(*issue));
  }

  // [effects]: one named choice per slot (docs/scene-format.md). The older
  // boolean keys (damping = true, tangential_friction, rolling_friction)
  // are still read: true keeps the default model, false means "none".
  void read_effects(const Reader& root) {
    Reader r(root.table("effects"), "effects", ctx_,
             {"gravity", "normal", "damping", "tangential", "rolling", "rolling_damping",
              "cohesion", "capillary", "fluid", "drag", "tangential_friction", "rolling_friction"});
    Effects& e = scene_.effects;
    e.gravity = r.vec3("gravity", e.gravity);
    r.choice("normal", "hertz", {"hertz"});
    if (r.is_boolean("damping"))
      e.damping = r.boolean("damping", true) ? DampingModel::Viscous : DampingModel::None;
    else
      e.damping = r.choice("damping", "viscous", {"viscous", "none"}) == "none"
                      ? DampingModel::None
                      : DampingModel::Viscous;
    legacy_pair(r, "tangential", "tangential_friction");
    legacy_pair(r, "rolling", "rolling_friction");
    if (r.has("tangential_friction"))
      e.tangential = r.boolean("tangential_friction", true) ? TangentialModel::Mindlin
                                                             : TangentialModel::None;
    else
      e.tangential = r.choice("tangential", "mindlin", {"mindlin", "none"}) == "none"
                         ? TangentialModel::None
                         : TangentialModel::Mindlin;
    if (r.has("rolling_friction")) {
      e.rolling = r.boolean("rolling_friction", true) ? RollingModel::ConstantTorque
                                                      : RollingModel::None;
    } else {
      const std::string rolling =
          r.choice("rolling", "constant_torque", {"constant_torque", "spring_dashpot", "none"});
      e.rolling = rolling == "none"             ? RollingModel::None
                  : rolling == "spring_dashpot" ? RollingModel::SpringDashpot
                                                : RollingModel::ConstantTorque;
    }
    if (e.rolling != RollingModel::SpringDashpot)
      r.forbid({"rolling_damping"}, "only allowed when rolling = \"spring_dashpot\"");
    e.rolling_damping = r.number("rolling_damping", e.rolling_damping);

    e.cohesion = r.choice("cohesion", "none", {"none", "capillary"}) == "capillary"
                     ? CohesionModel::Capillary
                     : CohesionModel::None;
    if (e.cohesion == CohesionModel::Capillary) {
      Reader c(r.table("capillary"), r.field("capillary"), ctx_,
               {"surface_tension", "contact_angle", "liquid_volume"});
      e.capillary.surface_tension = c.number("surface_tension", e.capillary.surface_tension);
      e.capillary.contact_angle = c.number("contact_angle", e.capillary.contact_angle);
      e.capillary.liquid_volume = c.number("liquid_volume");
    } else {
      r.forbid({"capillary"}, "only allowed when cohesion = \"capillary\"");
    }

    e.fluid = r.choice("fluid", "none", {"none", "drag"}) == "drag" ? FluidModel::Drag
                                                                  : FluidModel::None;
    if (e.fluid == FluidModel::Drag) {
      Reader f(r.table("drag"), r.field("drag"), ctx_, {"density", "viscosity", "velocity"});
      e.fluid_params.density = f.number("density");
      e.fluid_params.viscosity = f.number("viscosity");
      e.fluid_params.velocity = f.vec3("velocity", {});
    } else {
      r.forbid({"drag"}, "only allowed when fluid = \"drag\"");
    }
  }

  static void legacy_pair(const Reader& r, const char* key, const char* legacy) {
    if (r.has(key) && r.has(legacy))
      r.fail("conflicting_keys", legacy,
             std::string("give either ") + key + " or the older " + legacy + ", not both");
  }

  void read_numerics(const Reader& root) {
    Reader r(
        root.table("numerics"), "numerics", ctx_,
        {"precision", "dt", "dt_fraction", "force_dt", "duration", "skin", "neighbor_capacity"});
    Numerics& n = scene_.numerics;
    n.precision = r.choice("precision", "double", {"float", "double"}) == "float"
                      ? Precision::Float
                      : Precision::Double;
    n.dt = r.number("dt", n.dt);
    n.dt_fraction = r.number("dt_fraction", n.dt_fraction);
    n.force_dt = r.boolean("force_dt", n.force_dt);
    n.duration = r.number("duration");
    n.skin = r.number("skin", n.skin);
    const std::int64_t capacity = r.optional_integer("neighbor_capacity").value_or(0);
    if (capacity < 0 || capacity > 1'000'000)
      r.fail("out_of_range", "neighbor_capacity",
             std::to_string(capacity) + " is out of range, allowed 0 (automatic) or [4, 256]");
    n.neighbor_capacity = static_cast<int>(capacity);
  }

  void read_outputs(const Reader& root) {
    Reader r(root.table("output"), "output", ctx_,
             {"series_interval", "dump_interval", "checkpoint_interval", "dump_csv", "dump_vtk"});
    Outputs& o = scene_.outputs;
    o.series_interval = r.number("series_interval", o.series_interval);
    o.dump_interval = r.number("dump_interval", o.dump_interval);
    o.checkpoint_interval = r.number("checkpoint_interval", o.checkpoint_interval);
    o.dump_csv = r.boolean("dump_csv", o.dump_csv);
    o.dump_vtk = r.boolean("dump_vtk", o.dump_vtk);
  }

  void read_view(const Reader& root) {
    Reader r(root.table("view"), "view", ctx_,
             {"view", "color_by", "mode", "size", "chains", "threshold"});
    ViewHints& v = scene_.view;
    v.view = r.string("view", "");
    v.color_by = r.string("color_by", "");
    v.mode = r.string("mode", "");
    v.size = r.string("size", "");
    if (r.has("chains")) v.chains = r.boolean("chains", false);
    v.threshold = r.optional_number("threshold");
  }

  // Line of `field` in the document, or of its closest existing parent
  // ("walls[1]" for a defaulted "walls[1].velocity"); 0 when none.
  int line_for(std::string field) const {
    while (!field.empty()) {
      if (const toml::node* n = toml::at_path(*root_, field).node()) return line_of(n->source());
      const size_t cut = field.find_last_of(".[");
      if (cut == std::string::npos || cut == 0) break;
      field.resize(cut);
    }
    return 0;
  }

  // Issues about generated particles are reported at their generator.
  void note(SceneIssue issue) {
    size_t k = 0;
    if (std::sscanf(issue.field.c_str(), "particles[%zu]", &k) == 1 && k >= explicit_particles_) {
      issue.message = "generated particle " + std::to_string(k) + ": " + issue.message;
      issue.field = item("generators", generator_of_[k - explicit_particles_]);
    }
    ctx_.note(issue.code, line_for(issue.field), issue.field, issue.message);
  }
  // The reading cannot go on: this issue and those noted before it.
  [[noreturn]] void fail(SceneIssue issue) {
    note(std::move(issue));
    throw SceneError(ctx_.file, ctx_.found);
  }

  Context ctx_;
  const toml::table* root_ = nullptr;
  Scene scene_;
  size_t explicit_particles_ = 0;
  std::vector<size_t> generator_of_;  // per generated particle
};

// ---------------------------------------------------------------------------
// Writer.

std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (c < 0x20 || c == 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04X", c);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

// Shortest round-trip text, always a TOML float ("1.0", not "1").
std::string toml_float(double v) {
  std::string s = num(v);
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}

std::string toml_vec3(const Vec3& v) {
  return "[" + toml_float(v[0]) + ", " + toml_float(v[1]) + ", " + toml_float(v[2]) + "]";
}

bool is_default_zero(const Vec3& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return x == 0 && !std::signbit(x); });
}

const std::string& material_name(const Scene& s, int index, const std::string& field) {
  if (index < 0 || index >= static_cast<int>(s.materials.size()))
    throw SceneError("unknown_material", s.source_path, 0, field,
                     "material index " + std::to_string(index) + " does not exist");
  return s.materials[index].name;
}

class Writer {
 public:
  explicit Writer(const Scene& s) : s_(s) {}

  std::string write() {
    out_ << "# SimSols scene (written by to_toml; all particles explicit)\n";
    header("[scene]");
    line("name", toml_string(s_.name));
    if (!s_.description.empty()) line("description", toml_string(s_.description));
    for (const Material& m : s_.materials) write(m);
    for (size_t i = 0; i < s_.pair_overrides.size(); ++i) write(s_.pair_overrides[i], i);
    for (size_t i = 0; i < s_.walls.size(); ++i)
      if (!is_box_wall(i)) write(s_.walls[i], i);
    if (s_.shear_box) write_shear_box(*s_.shear_box);
    write_effects();
    write_numerics();
    write_outputs();
    write_view();
    for (size_t i = 0; i < s_.particles.size(); ++i) write(s_.particles[i], i);
    return out_.str();
  }

 private:
  void header(std::string_view h) { out_ << "\n" << h << "\n"; }
  void line(std::string_view key, const std::string& value) {
    out_ << key << " = " << value << "\n";
  }
  void line(std::string_view key, double value) { line(key, toml_float(value)); }
  void line(std::string_view key, bool value) { line(key, std::string(value ? "true" : "false")); }
  void line(std::string_view key, const Vec3& value) { line(key, toml_vec3(value)); }

  void write(const Material& m) {
    header("[[materials]]");
    line("name", toml_string(m.name));
    line("young_modulus", m.young_modulus);
    line("poisson_ratio", m.poisson_ratio);
    line("density", m.density);
    line("restitution", m.restitution);
    line("sliding_friction", m.sliding_friction);
    line("rolling_friction", m.rolling_friction);
  }

  void write(const PairOverride& o, size_t i) {
    const std::string f = item("interactions", i) + ".materials";
    header("[[interactions]]");
    line("materials", "[" + toml_string(material_name(s_, o.material_a, f)) + ", " +
                          toml_string(material_name(s_, o.material_b, f)) + "]");
    if (o.restitution) line("restitution", *o.restitution);
    if (o.sliding_friction) line("sliding_friction", *o.sliding_friction);
    if (o.rolling_friction) line("rolling_friction", *o.rolling_friction);
    if (o.liquid_volume) line("liquid_volume", *o.liquid_volume);
    if (o.contact_angle) line("contact_angle", *o.contact_angle);
  }

  void write(const Wall& w, size_t i) {
    header("[[walls]]");
    line("name", toml_string(w.name));
    line("type", toml_string(w.shape == WallShape::Rectangle ? "rectangle" : "plane"));
    line("material", toml_string(material_name(s_, w.material, item("walls", i) + ".material")));
    line("point", w.point);
    line("normal", w.normal);
    if (w.shape == WallShape::Rectangle) {
      line("axis_u", w.axis_u);
      line("half_u", w.half_u);
      line("half_v", w.half_v);
    }
    if (!is_default_zero(w.velocity)) line("velocity", w.velocity);
    if (w.servo.enabled && w.servo.mass > 0)
      line("servo", "{ target_force = " + toml_float(w.servo.target_force) +
                        ", mass = " + toml_float(w.servo.mass) + " }");
    else if (w.servo.enabled)
      line("servo", "{ target_force = " + toml_float(w.servo.target_force) +
                        ", gain = " + toml_float(w.servo.gain) +
                        ", max_speed = " + toml_float(w.servo.max_speed) +
                        (w.servo.integral_time > 0
                             ? ", integral_time = " + toml_float(w.servo.integral_time)
                             : std::string()) +
                        " }");
  }

  bool is_box_wall(size_t i) const {
    return s_.shear_box && static_cast<int>(i) >= s_.shear_box->first_wall &&
           static_cast<int>(i) < s_.shear_box->first_wall + kShearBoxWalls;
  }

  // The apparatus with its resolved values; its specimen is the explicit
  // particles below, so reading it back rebuilds the same walls.
  void write_shear_box(const ShearBox& b) {
    header("[shear_box]");
    line("length", b.length);
    line("width", b.width);
    line("split_height", b.split_height);
    line("gap", b.gap);
    line("wall_material", toml_string(material_name(s_, b.wall_material, "shear_box.wall_material")));
    line("normal_stress", b.normal_stress);
    line("shear_speed", b.shear_speed);
    line("inertial_number", b.inertial_number);
    line("shear_displacement", b.shear_displacement);
    line("loading", toml_string(b.loading == ShearBox::Loading::Servo ? "servo" : "dead_weight"));
    line("platen_mass", b.platen_mass);
    line("servo_gain", b.servo_gain);
    line("servo_max_speed", b.servo_max_speed);
    line("servo_integral_time", b.servo_integral_time);
    line("settle_time", b.settle_time);
    line("consolidate_time", b.consolidate_time);
    line("rows", std::to_string(b.rows));
    header("[shear_box.specimen]");
    line("method", toml_string("given"));
  }

  void write_effects() {
    const Effects& e = s_.effects;
    header("[effects]");
    line("gravity", e.gravity);
    line("normal", toml_string("hertz"));
    line("damping", toml_string(slot_name(e.damping)));
    line("tangential", toml_string(slot_name(e.tangential)));
    line("rolling", toml_string(slot_name(e.rolling)));
    if (e.rolling == RollingModel::SpringDashpot) line("rolling_damping", e.rolling_damping);
    line("cohesion", toml_string(slot_name(e.cohesion)));
    if (e.cohesion == CohesionModel::Capillary) {
      const Capillary& c = e.capillary;
      line("capillary", "{ surface_tension = " + toml_float(c.surface_tension) +
                            ", contact_angle = " + toml_float(c.contact_angle) +
                            ", liquid_volume = " + toml_float(c.liquid_volume) + " }");
    }
    if (e.fluid == FluidModel::Drag) {
      const Fluid& f = e.fluid_params;
      line("fluid", toml_string("drag"));
      line("drag", "{ density = " + toml_float(f.density) +
                        ", viscosity = " + toml_float(f.viscosity) +
                        ", velocity = " + toml_vec3(f.velocity) + " }");
    }
  }

  void write_numerics() {
    const Numerics& n = s_.numerics;
    header("[numerics]");
    line("precision", toml_string(n.precision == Precision::Float ? "float" : "double"));
    if (n.dt != 0 || std::signbit(n.dt)) line("dt", n.dt);
    line("dt_fraction", n.dt_fraction);
    line("force_dt", n.force_dt);
    line("duration", n.duration);
    line("skin", n.skin);
    line("neighbor_capacity", std::to_string(n.neighbor_capacity));
  }

  void write_outputs() {
    const Outputs& o = s_.outputs;
    header("[output]");
    line("series_interval", o.series_interval);
    line("dump_interval", o.dump_interval);
    line("checkpoint_interval", o.checkpoint_interval);
    line("dump_csv", o.dump_csv);
    line("dump_vtk", o.dump_vtk);
  }

  void write_view() {
    const ViewHints& v = s_.view;
    if (v.empty()) return;
    header("[view]");
    if (!v.view.empty()) line("view", toml_string(v.view));
    if (!v.color_by.empty()) line("color_by", toml_string(v.color_by));
    if (!v.mode.empty()) line("mode", toml_string(v.mode));
    if (!v.size.empty()) line("size", toml_string(v.size));
    if (v.chains) line("chains", *v.chains);
    if (v.threshold) line("threshold", *v.threshold);
  }

  void write(const Particle& p, size_t i) {
    header("[[particles]]");
    line("material",
         toml_string(material_name(s_, p.material, item("particles", i) + ".material")));
    line("radius", p.radius);
    line("position", p.position);
    if (!is_default_zero(p.velocity)) line("velocity", p.velocity);
    if (!is_default_zero(p.angular_velocity)) line("angular_velocity", p.angular_velocity);
  }

  const Scene& s_;
  std::ostringstream out_;
};

}  // namespace

Scene parse_scene(std::string_view text, const std::string& path_for_messages) {
  toml::table root;
  try {
    root = toml::parse(text, path_for_messages);
  } catch (const toml::parse_error& e) {
    throw SceneError("syntax", path_for_messages, line_of(e.source()), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  Scene scene = Loader(path_for_messages).load(root);
  scene.source_path = path_for_messages;
  scene.source_text = std::string(text);
  return scene;
}

Scene load_scene(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw SceneError("io", path, 0, "",
                     "cannot read the scene: no such file (or not a regular file)");
  if (require_scene_or_checkpoint(path, "a scene (TOML)") == InputKind::Checkpoint)
    throw SceneError("not_a_scene", path, 0, "",
                     "a SimSols checkpoint, not a scene: resume it with 'simsols run --resume "
                     "--out DIR' (DIR holding it as checkpoint.bin) or draw it with 'simsols "
                     "snapshot'");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in || in.bad()) throw SceneError("io", path, 0, "", "cannot read the scene file");
  return parse_scene(text.str(), path);
}

std::string to_toml(const Scene& scene) { return Writer(scene).write(); }

}  // namespace simsols
