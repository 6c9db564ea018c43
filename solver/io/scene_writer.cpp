// Scene -> TOML: every particle explicit, every double in its shortest
// round-trip form, so parse_scene(to_toml(s)) reproduces s bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "solver/apparatus/registry.h"
#include "solver/io/scene_toml.h"
#include "solver/io/scene_tables.h"
#include "solver/io/toml_reader.h"

namespace simsols {
namespace {

using scene_toml::item;
using scene_toml::num;

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

}  // namespace

namespace scene_toml {

void TableWriter::header(std::string_view h) { out_ << "\n" << h << "\n"; }
void TableWriter::line(std::string_view key, const std::string& toml_value) {
  out_ << key << " = " << toml_value << "\n";
}
void TableWriter::line(std::string_view key, double value) { line(key, toml_float(value)); }
void TableWriter::line(std::string_view key, bool value) {
  line(key, std::string(value ? "true" : "false"));
}
void TableWriter::line(std::string_view key, const Vec3& value) { line(key, toml_vec3(value)); }
void TableWriter::line(std::string_view key, const std::vector<double>& values) {
  std::string a = "[";
  for (size_t i = 0; i < values.size(); ++i) a += (i ? ", " : "") + toml_float(values[i]);
  line(key, a + "]");
}
void TableWriter::text(std::string_view key, std::string_view value) { line(key, toml_string(value)); }
void TableWriter::material(std::string_view key, int index, const std::string& field) {
  text(key, material_name(scene_, index, field));
}

// The settling friction and index void ratios (a target relative density
// is written as the friction found for it); the pour's rain is in the
// particles' positions and velocities.
void TableWriter::given_specimen(const std::string& table, const Preparation& p) {
  header("[" + table + ".specimen]");
  text("method", choice_name(Specimen::Method::Given));
  if (!p.friction && !p.rolling_friction && !p.e_min) return;
  header("[" + table + ".specimen.preparation]");
  if (p.friction) line("friction", *p.friction);
  if (p.rolling_friction) line("rolling_friction", *p.rolling_friction);
  if (p.e_min) line("e_min", *p.e_min);
  if (p.e_max) line("e_max", *p.e_max);
}

}  // namespace scene_toml

namespace {

class Writer {
 public:
  explicit Writer(const Scene& s) : s_(s), w_(s, out_) {}

  std::string write() {
    out_ << "# SimSols scene (written by to_toml; all particles explicit)\n";
    header("[scene]");
    line("name", toml_string(s_.name));
    if (!s_.description.empty()) line("description", toml_string(s_.description));
    for (const Material& m : s_.materials) write(m);
    for (size_t i = 0; i < s_.pair_overrides.size(); ++i) write(s_.pair_overrides[i], i);
    for (size_t i = 0; i < s_.walls.size(); ++i)
      if (!is_box_wall(i)) write(s_.walls[i], i);
    scene_toml::write_apparatus(w_);
    write_effects();
    write_numerics();
    write_outputs();
    write_view();
    // an apparatus rebuilds its membrane; otherwise its beads are particles
    const Membrane& m = s_.membrane;
    const bool built = s_.has_apparatus();
    for (size_t i = 0; i < s_.particles.size(); ++i) {
      const bool bead = int(i) >= m.first && int(i) < m.first + m.count();
      if (s_.particles[i].clump < 0 && !(built && bead)) write(s_.particles[i], i);
    }
    write_clumps();
    if (m.count() > 0 && !built) write_membrane();
    return out_.str();
  }

 private:
  void header(std::string_view h) { w_.header(h); }
  template <class V>
  void line(std::string_view key, const V& value) {
    w_.line(key, value);
  }

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
    line("type", toml_string(choice_name(w.shape)));
    line("material", toml_string(material_name(s_, w.material, item("walls", i) + ".material")));
    line("point", w.point);
    line("normal", w.normal);
    if (w.shape == WallShape::Rectangle) {
      line("axis_u", w.axis_u);
      line("half_u", w.half_u);
      line("half_v", w.half_v);
      if (w.tilts) line("tilts", "true");
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

  // The apparatus' walls are written as its table, which rebuilds them.
  bool is_box_wall(size_t i) const {
    const ApparatusKind* kind = apparatus_kind(s_);
    const int k = static_cast<int>(i), first = kind ? s_.cell()->first_wall : 0;
    return kind && k >= first && k < first + kind->walls;
  }

  void write_effects() {
    const Effects& e = s_.effects;
    header("[effects]");
    line("gravity", e.gravity);
    line("normal", toml_string("hertz"));
    line("damping", toml_string(choice_name(e.damping)));
    line("tangential", toml_string(choice_name(e.tangential)));
    line("rolling", toml_string(choice_name(e.rolling)));
    if (e.rolling == RollingModel::SpringDashpot) line("rolling_damping", e.rolling_damping);
    line("cohesion", toml_string(choice_name(e.cohesion)));
    if (e.cohesion == CohesionModel::Capillary) {
      const Capillary& c = e.capillary;
      line("capillary", "{ surface_tension = " + toml_float(c.surface_tension) +
                            ", contact_angle = " + toml_float(c.contact_angle) +
                            ", liquid_volume = " + toml_float(c.liquid_volume) + " }");
    }
    if (e.fluid == FluidModel::Drag) {
      const Fluid& f = e.fluid_params;
      line("fluid", toml_string(choice_name(e.fluid)));
      line("drag", "{ density = " + toml_float(f.density) +
                        ", viscosity = " + toml_float(f.viscosity) +
                        ", velocity = " + toml_vec3(f.velocity) + " }");
    }
  }

  void write_numerics() {
    const Numerics& n = s_.numerics;
    header("[numerics]");
    line("precision", toml_string(choice_name(n.precision)));
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

  // Grains, then clumps as placed (their members are rebuilt from them).
  void write_clumps() {
    for (const Grain& g : s_.grains) {
      if (!g.origin.empty()) out_ << "\n# " << g.name << ": " << g.origin;
      header("[[grains]]");
      line("name", toml_string(g.name));
      std::string rows = "[";
      for (size_t k = 0; k < g.spheres.size(); ++k) {
        rows += k ? ", [" : "[";
        for (int c = 0; c < 4; ++c) rows += (c ? ", " : "") + toml_float(g.spheres[k][c]);
        rows += "]";
      }
      line("spheres", rows + "]");
    }
    for (size_t i = 0; i < s_.clumps.size(); ++i) {
      const Clump& c = s_.clumps[i];
      header("[[clumps]]");
      line("grain", toml_string(s_.grains[c.grain].name));
      if (c.scale != 1) line("scale", c.scale);
      line("material", toml_string(material_name(s_, c.material, item("clumps", i) + ".material")));
      line("position", c.position);
      const auto& q = c.orientation;
      line("orientation", "[" + toml_float(q[0]) + ", " + toml_float(q[1]) + ", " + toml_float(q[2]) +
                              ", " + toml_float(q[3]) + "]");
      if (!is_default_zero(c.velocity)) line("velocity", c.velocity);
      if (!is_default_zero(c.angular_velocity)) line("angular_velocity", c.angular_velocity);
    }
  }

  void write_membrane() {
    const Membrane& m = s_.membrane;
    header("[membrane]");
    line("first", std::to_string(m.first));
    line("rows", std::to_string(m.rows));
    line("cols", std::to_string(m.cols));
    line("stiffness", m.stiffness);
    line("damping", m.damping);
    if (m.platen_wall >= 0) line("platen_wall", std::to_string(m.platen_wall));
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
  scene_toml::TableWriter w_;
};

}  // namespace

std::string to_toml(const Scene& scene) {
  if (!scene.placed())  // its generators and apparatus would be lost
    throw std::logic_error("to_toml: the scene '" + scene.name +
                           "' is read but not placed (place_scene)");
  return Writer(scene).write();
}

}  // namespace simsols
