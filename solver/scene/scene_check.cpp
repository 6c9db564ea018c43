// The semantic validation shared by scenes built in code and scenes loaded
// from TOML (see scene_check.h).
#include "solver/scene/scene_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "solver/common/errors.h"
#include "solver/common/number_text.h"
#include "solver/scene/contact_model.h"
#include "solver/scene/sphere_grid.h"

namespace simsols {

// ---------------------------------------------------------------------------
// Validation. Values out of range are collected (Found) and the checks go
// on; any other problem throws an Issue, which ends them.

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Tolerances (documented in docs/scene-format.md).
constexpr double kUnitTolerance = 1e-9;           // | |v| - 1 | for unit vectors
constexpr double kPerpendicularTolerance = 1e-6;  // |normal . axis_u|
constexpr double kMaxOverlapFraction = 0.01;      // of the smaller radius

struct Issue {
  SceneIssue issue;
};

[[noreturn]] void fail(std::string code, std::string field, std::string message) {
  throw Issue{{std::move(code), std::move(field), std::move(message)}};
}

// Values out of range or not finite: collected, the checks go on.
using Found = std::vector<SceneIssue>;
void note(Found& found, std::string code, std::string field, std::string message) {
  found.push_back({std::move(code), std::move(field), std::move(message)});
}

// A real interval with open or closed ends, printed as "[0, 0.5)".
struct Interval {
  double lo, hi;
  bool lo_open, hi_open;
  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string str() const {
    return std::string(lo_open ? "(" : "[") + shortest_number(lo) + ", " +
           shortest_number(hi) + (hi_open ? ")" : "]");
  }
};

constexpr Interval kPositive{0, kInf, true, true};
constexpr Interval kNonNegative{0, kInf, false, true};
constexpr Interval kRestitution{kMinRestitution, 1, false, false};
constexpr Interval kContactAngle{0, 1.5707963267948966, false, true};  // [0, pi/2)

std::string at(const std::string& base, size_t i) { return base + "[" + std::to_string(i) + "]"; }

void check_number(Found& found, const std::string& field, double v, const Interval& allowed,
                  const std::string& why = "") {
  if (!std::isfinite(v))
    note(found, "not_finite", field, shortest_number(v) + " is not a finite number");
  else if (!allowed.contains(v))
    note(found, "out_of_range", field,
         shortest_number(v) + " is out of range, allowed " + allowed.str() + why);
}

// Why a restitution below kMinRestitution is refused (docs/model.md).
void check_restitution(Found& found, const std::string& field, double v) {
  const std::string why =
      v < kMinRestitution
          ? " (the Hertz contact with its d^{1/4} dashpot always rebounds: e = 0 would need "
            "infinite damping, and below " + shortest_number(kMinRestitution) +
            " a fast contact lasts too few time steps for e to come out as asked)"
          : "";
  check_number(found, field, v, kRestitution, why);
}

// False (and noted) when a component is not finite.
bool check_vector(Found& found, const std::string& field, const Vec3& v) {
  for (size_t k = 0; k < 3; ++k)
    if (!std::isfinite(v[k])) {
      note(found, "not_finite", field,
           "component " + std::to_string(k) + " is " + shortest_number(v[k]) +
               ", not a finite number");
      return false;
    }
  return true;
}


void check_material_ref(const Scene& s, const std::string& field, int index) {
  if (index < 0 || index >= static_cast<int>(s.materials.size()))
    fail("unknown_material", field,
         "material index " + std::to_string(index) + " does not exist, allowed [0, " +
             std::to_string(s.materials.size()) + ")");
}

void check_name(const std::string& field, const std::string& name, std::set<std::string>& seen) {
  if (name.empty()) fail("missing_field", field, "the name must not be empty");
  if (!seen.insert(name).second)
    fail("duplicate_name", field, "the name '" + name + "' is already used");
}

void check_materials(const Scene& s, Found& found) {
  std::set<std::string> names;
  for (size_t i = 0; i < s.materials.size(); ++i) {
    const Material& m = s.materials[i];
    const std::string f = at("materials", i);
    check_name(f + ".name", m.name, names);
    check_number(found, f + ".young_modulus", m.young_modulus, kPositive);
    check_number(found, f + ".poisson_ratio", m.poisson_ratio, {0, 0.5, false, true});
    check_number(found, f + ".density", m.density, kPositive);
    check_restitution(found, f + ".restitution", m.restitution);
    check_number(found, f + ".sliding_friction", m.sliding_friction, kNonNegative);
    check_number(found, f + ".rolling_friction", m.rolling_friction, kNonNegative);
  }
}

void check_pair_overrides(const Scene& s, Found& found) {
  std::set<std::pair<int, int>> pairs;
  for (size_t i = 0; i < s.pair_overrides.size(); ++i) {
    const PairOverride& o = s.pair_overrides[i];
    const std::string f = at("interactions", i);
    check_material_ref(s, f + ".materials", o.material_a);
    check_material_ref(s, f + ".materials", o.material_b);
    if (!pairs.insert(std::minmax(o.material_a, o.material_b)).second)
      fail("duplicate_name", f + ".materials",
           "the pair ('" + s.materials[o.material_a].name + "', '" +
               s.materials[o.material_b].name + "') already has an interaction");
    if (o.restitution) check_restitution(found, f + ".restitution", *o.restitution);
    if (o.sliding_friction)
      check_number(found, f + ".sliding_friction", *o.sliding_friction, kNonNegative);
    if (o.rolling_friction)
      check_number(found, f + ".rolling_friction", *o.rolling_friction, kNonNegative);
    if (o.liquid_volume) check_number(found, f + ".liquid_volume", *o.liquid_volume, kPositive);
    if (o.contact_angle) check_number(found, f + ".contact_angle", *o.contact_angle, kContactAngle);
  }
}

void check_particles(const Scene& s, Found& found) {
  if (s.particles.empty() && s.placed())
    fail("no_particles", "particles",
         "the scene has no particles; add [[particles]] or [[generators]]");
  for (size_t i = 0; i < s.particles.size(); ++i) {
    const Particle& p = s.particles[i];
    const std::string f = at("particles", i);
    check_material_ref(s, f + ".material", p.material);
    check_number(found, f + ".radius", p.radius, kPositive);
    check_vector(found, f + ".position", p.position);
    check_vector(found, f + ".velocity", p.velocity);
    check_vector(found, f + ".angular_velocity", p.angular_velocity);
  }
}

void check_unit(Found& found, const std::string& field, const Vec3& v, const char* zero_code) {
  if (!check_vector(found, field, v)) return;
  const double n = norm(v);
  if (n == 0) fail(zero_code, field, "must not be the zero vector");
  if (std::abs(n - 1) > kUnitTolerance)
    fail("bad_vector", field,
         "must be a unit vector, its length is " + shortest_number(n) + " (allowed 1 +- " +
             shortest_number(kUnitTolerance) + ")");
}

void check_wall(const Scene& s, size_t i, std::set<std::string>& names, Found& found) {
  const Wall& w = s.walls[i];
  const std::string f = at("walls", i);
  check_name(f + ".name", w.name, names);
  check_material_ref(s, f + ".material", w.material);
  check_vector(found, f + ".point", w.point);
  check_vector(found, f + ".velocity", w.velocity);
  check_unit(found, f + ".normal", w.normal, "zero_normal");
  if (w.servo.enabled) {
    check_number(found, f + ".servo.target_force", w.servo.target_force, kPositive);
    check_number(found, f + ".servo.mass", w.servo.mass, kNonNegative);
    if (w.servo.mass == 0) {
      check_number(found, f + ".servo.gain", w.servo.gain, kPositive);
      check_number(found, f + ".servo.max_speed", w.servo.max_speed, kPositive);
      check_number(found, f + ".servo.integral_time", w.servo.integral_time, kNonNegative);
    }
    if (norm(w.velocity) != 0)
      fail("conflicting_keys", f + ".velocity",
           "a servo-controlled wall moves by itself; remove its velocity");
  }
  if (w.tilts && w.shape != WallShape::Rectangle)
    fail("conflicting_keys", f + ".tilts", "only a rectangle may tilt (a plane has no centre to turn about)");
  if (w.shape != WallShape::Rectangle) return;
  check_unit(found, f + ".axis_u", w.axis_u, "bad_vector");
  const double d = dot(w.normal, w.axis_u);
  if (std::abs(d) > kPerpendicularTolerance)
    fail("bad_vector", f + ".axis_u",
         "must be perpendicular to the normal: normal . axis_u = " + shortest_number(d) +
             ", allowed |.| <= " + shortest_number(kPerpendicularTolerance));
  check_number(found, f + ".half_u", w.half_u, kPositive);
  check_number(found, f + ".half_v", w.half_v, kPositive);
}

std::array<Vec3, 4> rectangle_corners(const Wall& w) {
  const Vec3 v = cross(w.normal, w.axis_u);
  std::array<Vec3, 4> c{};
  const double su[4] = {1, 1, -1, -1}, sv[4] = {1, -1, 1, -1};
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d)
      c[k][d] = w.point[d] + su[k] * w.half_u * w.axis_u[d] + sv[k] * w.half_v * v[d];
  return c;
}

bool same_point(const Vec3& a, const Vec3& b) {
  return norm(sub(a, b)) <= 1e-9 * (1 + norm(a) + norm(b));
}

bool identical_walls(const Wall& a, const Wall& b) {
  if (a.shape != b.shape) return false;
  if (a.shape == WallShape::Plane)
    return dot(a.normal, b.normal) > 1 - 1e-12 && std::abs(dot(sub(b.point, a.point), a.normal)) <=
                                                      1e-9 * (1 + norm(a.point) + norm(b.point));
  const auto ca = rectangle_corners(a), cb = rectangle_corners(b);
  return std::all_of(ca.begin(), ca.end(), [&](const Vec3& p) {
    return std::any_of(cb.begin(), cb.end(), [&](const Vec3& q) { return same_point(p, q); });
  });
}

double smallest_radius(const Scene& s) {
  double r = kInf;
  for (const Particle& p : s.particles) r = std::min(r, p.radius);
  return r;
}

// Two walls overlap when they are identical, or when they are planes with
// opposite normals whose allowed half-spaces leave a gap smaller than the
// smallest particle diameter.
void check_wall_pair(const Scene& s, size_t i, size_t j) {
  const Wall& a = s.walls[i];
  const Wall& b = s.walls[j];
  const std::string f = at("walls", j);
  if (identical_walls(a, b))
    fail("overlapping_walls", f, "is identical to " + at("walls", i) + " ('" + a.name + "')");
  if (a.shape != WallShape::Plane || b.shape != WallShape::Plane) return;
  if (dot(a.normal, b.normal) > -1 + 1e-12) return;
  const double gap = dot(sub(b.point, a.point), a.normal);
  // before placing, only that they do not cross (place_scene checks again)
  const double diameter = s.placed() ? 2 * smallest_radius(s) : 0;
  if (gap < diameter)
    fail("overlapping_walls", f,
         "faces " + at("walls", i) + " ('" + a.name + "') with a gap of " +
             shortest_number(gap) + " m between their half-spaces; allowed >= " +
             shortest_number(diameter) + " m (the smallest particle diameter)");
}

void check_walls(const Scene& s, Found& found) {
  if (s.walls.size() > kMaxWalls)
    fail("out_of_range", at("walls", kMaxWalls),
         std::to_string(s.walls.size()) + " walls; at most " + std::to_string(kMaxWalls) +
             " are allowed");
  std::set<std::string> names;
  for (size_t i = 0; i < s.walls.size(); ++i) check_wall(s, i, names, found);
  for (size_t j = 0; j < s.walls.size(); ++j)
    for (size_t i = 0; i < j; ++i) check_wall_pair(s, i, j);
}

void check_numerics(const Scene& s, Found& found) {
  const Numerics& n = s.numerics;
  check_number(found, "numerics.dt", n.dt, kNonNegative);
  check_number(found, "numerics.dt_fraction", n.dt_fraction, {0, kMaxDtFraction, true, false});
  check_number(found, "numerics.duration", n.duration, kPositive);
  check_number(found, "numerics.skin", n.skin, kNonNegative);
  if (n.neighbor_capacity != 0 && (n.neighbor_capacity < 4 || n.neighbor_capacity > 256))
    note(found, "out_of_range", "numerics.neighbor_capacity",
         std::to_string(n.neighbor_capacity) +
             " is out of range, allowed 0 (automatic) or [4, 256]");
  if (n.precision != Precision::Float && n.precision != Precision::Double)
    fail("bad_enum", "numerics.precision", "allowed values: \"float\", \"double\"");
}

void check_effects(const Scene& s, Found& found) {
  const Effects& e = s.effects;
  check_vector(found, "effects.gravity", e.gravity);
  check_number(found, "effects.rolling_damping", e.rolling_damping, {0, 1, false, false});
  if (e.cohesion == CohesionModel::Capillary) {
    check_number(found, "effects.capillary.surface_tension", e.capillary.surface_tension, kPositive);
    check_number(found, "effects.capillary.contact_angle", e.capillary.contact_angle, kContactAngle);
    check_number(found, "effects.capillary.liquid_volume", e.capillary.liquid_volume, kPositive);
    // pairs within the rupture distance must be in the neighbour lists, which
    // hold pairs within skin and stay valid while each bead moves < skin/4
    const double need = 2 * s.rupture_distance();
    if (s.numerics.skin > 0 && s.numerics.skin < need)
      fail("out_of_range", "numerics.skin",
           shortest_number(s.numerics.skin) + " m is out of range, allowed [" +
               shortest_number(need) +
               ", inf) (twice the capillary rupture distance), or 0 (automatic)");
  }
  if (e.fluid == FluidModel::Drag) {
    check_number(found, "effects.drag.density", e.fluid_params.density, kNonNegative);
    check_number(found, "effects.drag.viscosity", e.fluid_params.viscosity, kPositive);
    check_vector(found, "effects.drag.velocity", e.fluid_params.velocity);
  }
}

void check_outputs(const Scene& s, Found& found) {
  check_number(found, "output.series_interval", s.outputs.series_interval, kNonNegative);
  check_number(found, "output.dump_interval", s.outputs.dump_interval, kNonNegative);
  check_number(found, "output.checkpoint_interval", s.outputs.checkpoint_interval, kNonNegative);
}

// O(N): a grid over the particles' box (dense cell lists, sphere_grid.h),
// cells one mean diameter wide, each sphere checked against those within
// its radius plus the largest. The spheres of one clump overlap by design,
// the beads of a membrane may (they never touch each other).
void check_particle_overlaps(const Scene& s) {
  // centre, radius and group (a clump's, or the membrane's after them),
  // packed: the particles themselves are too large for the cache at a
  // million beads
  struct Packed {
    Vec3 c;
    double r;
    int group;
  };
  const int membrane = static_cast<int>(s.clumps.size());
  std::vector<Packed> packed;
  packed.reserve(s.particles.size());
  double r_max = 0, r_sum = 0;
  Vec3 lo{}, hi{};
  for (size_t i = 0; i < s.particles.size(); ++i) {
    const Particle& p = s.particles[i];
    const bool bead = int(i) >= s.membrane.first && int(i) < s.membrane.first + s.membrane.count();
    r_max = std::max(r_max, p.radius);
    r_sum += p.radius;
    for (int k = 0; k < 3; ++k) {
      lo[k] = packed.empty() ? p.position[k] : std::min(lo[k], p.position[k]);
      hi[k] = packed.empty() ? p.position[k] : std::max(hi[k], p.position[k]);
    }
    packed.push_back({p.position, p.radius, bead ? membrane : p.clump});
  }
  // cells one mean diameter wide, each sphere's search as wide as it may touch
  SphereGrid grid(2 * r_sum / double(packed.size()), packed.size(), lo, hi);
  for (size_t i = 0; i < packed.size(); ++i) {
    const Packed& p = packed[i];
    grid.any_within(p.c, p.r + r_max, [&](int j) {
      const Packed& q = packed[static_cast<size_t>(j)];
      const double d2 = dot(sub(p.c, q.c), sub(p.c, q.c)), reach = p.r + q.r;
      if (d2 >= reach * reach) return false;  // apart or touching
      if (p.group >= 0 && p.group == q.group) return false;  // one rigid grain, one membrane
      const double overlap = reach - std::sqrt(d2);
      const double limit = kMaxOverlapFraction * std::min(p.r, q.r);
      if (overlap > limit)
        fail("overlapping_particles", at("particles", i),
             "overlaps " + at("particles", j) + " by " + shortest_number(overlap) +
                 " m; allowed at most 1% of the smaller radius (" + shortest_number(limit) +
                 " m)");
      return false;
    });
    grid.insert(static_cast<int>(i), p.c);
  }
}

// A bead created deep in a wall would be shot out at once (a bead whose
// centre lies on a plane overlaps it by its radius): refused like
// overlapping beads. Planes are one-sided (a centre behind one is ignored
// by the solver too); rectangles are two-sided plates.
}  // namespace

namespace {

void check_wall_overlaps(const Scene& s) {
  for (size_t w = 0; w < s.walls.size(); ++w) {
    const Wall& wall = s.walls[w];
    for (size_t i = 0; i < s.particles.size(); ++i) {
      const Particle& p = s.particles[i];
      const double dist = wall_distance(wall, wall.point, p.position);
      if (dist < 0) continue;  // behind a plane
      const double overlap = p.radius - dist, limit = kMaxOverlapFraction * p.radius;
      if (overlap > limit)
        fail("overlapping_wall", at("particles", i),
             "overlaps " + at("walls", w) + " ('" + wall.name + "') by " +
                 shortest_number(overlap) + " m; allowed at most 1% of its radius (" +
                 shortest_number(limit) + " m)");
    }
  }
}

void check_time_step(const Scene& s) {
  const Numerics& n = s.numerics;
  if (n.dt <= 0 || n.force_dt) return;
  const double rayleigh = rayleigh_time_step(s);
  const double limit = kMaxDtFraction * rayleigh;
  if (n.dt > limit)
    fail("dt_above_limit", "numerics.dt",
         shortest_number(n.dt) + " s is above the stability limit " +
             shortest_number(limit) + " s (" + shortest_number(kMaxDtFraction) +
             " x Rayleigh time step " + shortest_number(rayleigh) +
             " s); lower dt, or set numerics.force_dt = true to run anyway");
}

}  // namespace

std::vector<SceneIssue> find_scene_issues(const Scene& scene) {
  Found found;
  try {
    check_materials(scene, found);
    check_pair_overrides(scene, found);
    check_particles(scene, found);
    check_walls(scene, found);
    check_numerics(scene, found);
    check_effects(scene, found);
    check_outputs(scene, found);
    // the checks below need valid values, and every sphere and wall placed
    if (!found.empty() || !scene.placed()) return found;
    check_particle_overlaps(scene);
    check_wall_overlaps(scene);
    check_time_step(scene);
  } catch (Issue& e) {
    found.push_back(std::move(e.issue));
  }
  return found;
}

std::optional<SceneIssue> find_scene_issue(const Scene& scene) {
  std::vector<SceneIssue> all = find_scene_issues(scene);
  if (all.empty()) return std::nullopt;
  return std::move(all[0]);
}

void validate_scene(const Scene& scene, const std::string& file) {
  std::vector<SceneProblem> all;
  for (SceneIssue& i : find_scene_issues(scene))
    all.push_back({std::move(i.code), 0, std::move(i.field), std::move(i.message)});
  if (!all.empty()) throw SceneError(file, std::move(all));
}

}  // namespace simsols

