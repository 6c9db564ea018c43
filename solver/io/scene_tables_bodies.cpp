// [scene], [[materials]], [[interactions]], [[particles]], [[walls]],
// [membrane]: what
// a scene is made of, read table by table (docs/scene-format.md).
#include "solver/io/scene_tables.h"

#include <cmath>


namespace simsols::scene_toml {

void read_info(const Reader& root, Scene& scene) {
  Reader r = root.sub("scene", {"name", "description"});
  scene.name = r.string("name", scene.name);
  scene.description = r.string("description", "");
}

void read_materials(const Reader& root, Scene& scene) {
  const auto tables = root.tables("materials");
  for (size_t i = 0; i < tables.size(); ++i) {
    Reader r(*tables[i], item("materials", i), root.context(),
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
    scene.materials.push_back(m);
  }
}

void read_interactions(const Reader& root, Scene& scene) {
  const auto tables = root.tables("interactions");
  for (size_t i = 0; i < tables.size(); ++i) {
    Reader r(*tables[i], item("interactions", i), root.context(),
             {"materials", "restitution", "sliding_friction", "rolling_friction", "liquid_volume",
              "contact_angle"});
    PairOverride o;
    std::tie(o.material_a, o.material_b) = r.material_pair("materials", scene);
    o.restitution = r.optional_number("restitution");
    o.sliding_friction = r.optional_number("sliding_friction");
    o.rolling_friction = r.optional_number("rolling_friction");
    o.liquid_volume = r.optional_number("liquid_volume");
    o.contact_angle = r.optional_number("contact_angle");
    scene.pair_overrides.push_back(o);
  }
}

void read_particles(const Reader& root, Scene& scene) {
  const auto tables = root.tables("particles");
  for (size_t i = 0; i < tables.size(); ++i) {
    Reader r(*tables[i], item("particles", i), root.context(),
             {"material", "radius", "position", "velocity", "angular_velocity"});
    Particle p;
    p.material = r.material("material", scene);
    p.radius = r.number("radius");
    p.position = r.vec3("position");
    p.velocity = r.vec3("velocity", {});
    p.angular_velocity = r.vec3("angular_velocity", {});
    scene.particles.push_back(p);
  }
}

void read_walls(const Reader& root, Scene& scene) {
  const auto tables = root.tables("walls");
  for (size_t i = 0; i < tables.size(); ++i) {
    Reader r(*tables[i], item("walls", i), root.context(),
             {"name", "type", "material", "point", "normal", "axis_u", "half_u", "half_v",
              "tilts", "velocity", "servo"});
    Wall w;
    w.name = r.string("name", "wall" + std::to_string(i));
    const bool rectangle = r.choice("type", WallShape::Plane) == WallShape::Rectangle;
    if (!rectangle)
      r.forbid({"axis_u", "half_u", "half_v", "tilts"}, "only allowed when type = \"rectangle\"");
    w.material = r.material("material", scene);
    w.point = r.vec3("point");
    w.normal = normalized(r.vec3("normal"));
    w.velocity = r.vec3("velocity", {});
    if (r.has("servo")) {
      Reader sv = r.sub("servo", {"target_force", "gain", "max_speed", "integral_time", "mass"});
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
      w.tilts = r.boolean("tilts", false);
    }
    scene.walls.push_back(w);
  }
}

// [membrane]: particles already listed, tied into a membrane (scene.h,
// Membrane). An apparatus that builds one (triaxial cell = "membrane")
// writes its table instead.
void read_membrane(const Reader& root, Scene& scene) {
  if (!root.has("membrane")) return;
  Reader r = root.sub("membrane", {"first", "rows", "cols", "stiffness", "damping", "platen_wall"});
  Membrane& m = scene.membrane;
  const std::int64_t n = std::ssize(scene.particles);
  const std::int64_t first = r.integer("first"), rows = r.integer("rows"), cols = r.integer("cols");
  r.check_range("first", double(first), first >= 0 && first < n, "[0, particles - 1]");
  r.check_range("rows", double(rows), rows >= 3 && cols >= 3 && rows * cols <= n - first,
                "[3, ...], with cols >= 3 and rows x cols particles from first on");
  m.first = int(first);
  m.rows = int(rows);
  m.cols = int(cols);
  m.stiffness = r.number("stiffness");
  r.check_range("stiffness", m.stiffness, m.stiffness > 0 && m.stiffness < 1e9, "(0, 1e9) N/m");
  m.damping = r.number("damping", 0.5);
  r.check_range("damping", m.damping, m.damping >= 0 && m.damping <= 1, "[0, 1] of critical");
  const std::int64_t platen = r.optional_integer("platen_wall").value_or(-1);
  r.check_range("platen_wall", double(platen), platen >= -1 && platen < std::ssize(scene.walls),
                "[-1, walls - 1] (-1: the last row held still)");
  m.platen_wall = int(platen);
}

}  // namespace simsols::scene_toml
