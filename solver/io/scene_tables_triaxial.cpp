// [triaxial]: a cuboid specimen between six rigid plates (docs/triaxial.md),
// expanded into walls and beads by build_triaxial().
#include "solver/io/scene_tables.h"

namespace simsols::scene_toml {

void read_triaxial(const Reader& root, Scene& scene) {
  Reader r = root.sub("triaxial",
                      {"length", "width", "wall_material", "confining_stress", "path", "b_value",
                       "axial_strain", "strain_rate", "inertial_number", "settle_time",
                       "consolidate_time", "servo_gain", "servo_max_speed",
                       "servo_integral_time", "rows", "cell", "membrane_stiffness",
                       "membrane_spacing", "specimen"});
  Triaxial t;
  t.length = r.number("length", t.length);
  t.width = r.number("width", t.width);
  t.wall_material = read_wall_material(r, scene, t.wall_material);
  t.confining_stress = r.number("confining_stress", t.confining_stress);
  t.path = r.choice("path", t.path);
  if (t.path != Triaxial::Path::TrueTriaxial)
    r.forbid({"b_value"}, "only allowed when path = \"true_triaxial\"");
  t.b_value = r.number("b_value", t.b_value);
  t.cell = r.choice("cell", t.cell);
  if (t.cell == Triaxial::Cell::Rigid)
    r.forbid({"membrane_stiffness", "membrane_spacing"}, "only allowed when cell = \"membrane\"");
  else if (t.path != Triaxial::Path::ConstantSigma3)
    r.fail("conflicting_keys", "cell",
           "a membrane holds one cell pressure: use path = \"constant_sigma3\" with cell = \"membrane\"");
  t.membrane_stiffness = r.number("membrane_stiffness", t.membrane_stiffness);
  t.membrane_spacing = r.number("membrane_spacing", t.membrane_spacing);
  t.axial_strain = r.number("axial_strain", t.axial_strain);
  t.strain_rate = r.number("strain_rate", t.strain_rate);
  t.inertial_number = r.number("inertial_number", t.inertial_number);
  t.settle_time = r.number("settle_time", t.settle_time);
  t.consolidate_time = r.number("consolidate_time", t.consolidate_time);
  t.servo_gain = r.number("servo_gain", t.servo_gain);
  t.servo_max_speed = r.number("servo_max_speed", t.servo_max_speed);
  t.servo_integral_time = r.number("servo_integral_time", t.servo_integral_time);
  const std::int64_t rows = r.optional_integer("rows").value_or(t.rows);
  if (rows < 10 || rows > 1000000)
    r.fail("out_of_range", "rows", std::to_string(rows) + " is out of range, allowed [10, 1000000]");
  t.rows = static_cast<int>(rows);
  t.specimen = read_specimen(r, scene);
  scene.apparatus = t;
}

// Its resolved values (scene_tables.h: the walls are rebuilt from them).
void write_triaxial(TableWriter& w) {
  const Triaxial& t = *w.scene().apparatus_as<Triaxial>();
  w.header("[triaxial]");
  w.line("length", t.length);
  w.line("width", t.width);
  w.material("wall_material", t.wall_material, "triaxial.wall_material");
  w.line("confining_stress", t.confining_stress);
  w.text("path", choice_name(t.path));
  if (t.path == Triaxial::Path::TrueTriaxial) w.line("b_value", t.b_value);
  if (t.cell == Triaxial::Cell::Membrane) {
    w.text("cell", choice_name(t.cell));
    w.line("membrane_stiffness", t.membrane_stiffness);
    w.line("membrane_spacing", t.membrane_spacing);
  }
  w.line("axial_strain", t.axial_strain);
  w.line("strain_rate", t.strain_rate);
  w.line("inertial_number", t.inertial_number);
  w.line("settle_time", t.settle_time);
  w.line("consolidate_time", t.consolidate_time);
  w.line("servo_gain", t.servo_gain);
  w.line("servo_max_speed", t.servo_max_speed);
  w.line("servo_integral_time", t.servo_integral_time);
  w.line("rows", std::to_string(t.rows));
  w.given_specimen("triaxial", t.specimen.preparation);
}

}  // namespace simsols::scene_toml
