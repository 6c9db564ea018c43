// [periodic_cell]: a specimen in a periodic cell (docs/periodic-cell.md),
// its gas placed by build_periodic_cell().
#include <string>
#include <vector>

#include "solver/io/scene_tables.h"

namespace simsols::scene_toml {
namespace {

const std::vector<std::string> kTests = {"simple_shear", "triaxial", "isotropic", "oedometric"};
const std::vector<std::string> kPaths = {"constant_sigma3", "constant_p"};

template <class E>
E index_of(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<E>(i);
  return static_cast<E>(0);
}

}  // namespace

void read_periodic_cell(const Reader& root, Scene& scene) {
  Reader r = root.sub("periodic_cell",
                      {"particles", "diameter", "size_spread", "material", "seed",
                       "start_solid_fraction", "preparation_friction", "preparation_restitution",
                       "preparation_rolling_friction",
                       "pressure", "test", "path",
                       "inertial_number", "compression_inertial_number", "shear_strain",
                       "axial_strain", "vertical_stress", "row_strain", "given", "edges"});
  PeriodicCell c;
  const std::int64_t n = r.optional_integer("particles").value_or(c.particles);
  if (n < 8 || n > 10000000)
    r.fail("out_of_range", "particles", std::to_string(n) + " is out of range, allowed [8, 10000000]");
  c.particles = static_cast<int>(n);
  c.diameter = r.number("diameter", c.diameter);
  c.size_spread = r.number("size_spread", c.size_spread);
  if (r.has("material")) c.material = r.material("material", scene);
  c.seed = r.optional_integer("seed").value_or(c.seed);
  c.start_solid_fraction = r.number("start_solid_fraction", c.start_solid_fraction);
  c.preparation_friction = r.number("preparation_friction", c.preparation_friction);
  c.preparation_restitution = r.number("preparation_restitution", c.preparation_restitution);
  c.preparation_rolling_friction = r.optional_number("preparation_rolling_friction");
  c.pressure = r.number("pressure", c.pressure);
  c.test = index_of<PeriodicCell::Test>(kTests, r.choice("test", kTests[0], kTests));
  c.path = index_of<PeriodicCell::Path>(kPaths, r.choice("path", kPaths[0], kPaths));
  c.vertical_stress = r.number("vertical_stress", c.vertical_stress);
  c.inertial_number = r.number("inertial_number", c.inertial_number);
  c.compression_inertial_number = r.number("compression_inertial_number", c.compression_inertial_number);
  c.shear_strain = r.number("shear_strain", c.shear_strain);
  c.axial_strain = r.number("axial_strain", c.axial_strain);
  c.row_strain = r.number("row_strain", c.row_strain);
  c.given = r.boolean("given", false);
  if (c.given) {
    const std::vector<double> e = r.numbers("edges", {});
    if (e.size() != 9) r.fail("out_of_range", "edges", "the cell's nine edge components (row-major) are needed with given = true");
    std::copy(e.begin(), e.end(), c.edges.begin());
  }
  scene.apparatus = c;
  // a periodic cell has no gravity: off unless [effects] asked for another one
  const Vec3 g = scene.effects.gravity, standard = Effects{}.gravity;
  if (g != Vec3{0, 0, 0} && g != standard)
    r.context().fail("out_of_range", 0, "effects.gravity",
                     "a periodic cell has no gravity: leave it out or set [0, 0, 0]");
  scene.effects.gravity = {0, 0, 0};
  // the cell is known to be periodic from here on (the kernels' options do
  // not change when it is placed); build_periodic_cell gives it its edges
  scene.periodic = PeriodicBox{{}, {0, 0, 0}, c.preparation_friction, c.preparation_restitution};
}

// Its resolved values; the specimen as placed (the scene's particles and the
// cell's edges), so the same cell is read back.
void write_periodic_cell(TableWriter& w) {
  const PeriodicCell& c = *w.scene().apparatus_as<PeriodicCell>();
  w.header("[periodic_cell]");
  w.line("particles", std::to_string(c.particles));
  w.line("diameter", c.diameter);
  w.line("size_spread", c.size_spread);
  w.material("material", c.material, "periodic_cell.material");
  w.line("seed", std::to_string(c.seed));
  w.line("start_solid_fraction", c.start_solid_fraction);
  w.line("preparation_friction", c.preparation_friction);
  w.line("preparation_restitution", c.preparation_restitution);
  if (c.preparation_rolling_friction)
    w.line("preparation_rolling_friction", *c.preparation_rolling_friction);
  w.line("pressure", c.pressure);
  w.text("test", kTests[static_cast<int>(c.test)]);
  w.text("path", kPaths[static_cast<int>(c.path)]);
  w.line("inertial_number", c.inertial_number);
  w.line("compression_inertial_number", c.compression_inertial_number);
  w.line("shear_strain", c.shear_strain);
  w.line("axial_strain", c.axial_strain);
  if (c.vertical_stress > 0) w.line("vertical_stress", c.vertical_stress);
  w.line("row_strain", c.row_strain);
  w.line("given", true);
  const std::optional<PeriodicBox>& box = w.scene().periodic;
  const std::array<double, 9> e = box ? box->edges : c.edges;
  w.line("edges", std::vector<double>(e.begin(), e.end()));
}

}  // namespace simsols::scene_toml
