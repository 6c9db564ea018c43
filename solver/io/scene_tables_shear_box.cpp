// [shear_box]: the direct shear apparatus (docs/shear-box.md), built into
// walls and beads by build_shear_box() (registry.h); its specimen is read
// by read_specimen (scene_tables_specimen.cpp).
#include "solver/io/scene_tables.h"

namespace simsols::scene_toml {

void read_shear_box(const Reader& root, Scene& scene) {
  Reader r = root.sub("shear_box",
                      {"length", "width", "split_height", "gap", "wall_material", "insert_material", "normal_stress",
                       "shear_speed", "inertial_number", "shear_displacement", "loading",
                       "platen_mass", "servo_gain", "servo_max_speed", "servo_integral_time",
                       "upper_half", "upper_half_weight", "cap", "settle_time", "consolidate_time",
                       "rows", "specimen"});
  ShearBox b;
  b.length = r.number("length", b.length);
  b.width = r.number("width", b.width);
  b.split_height = r.number("split_height", b.split_height);
  b.gap = r.number("gap", b.gap);
  b.wall_material = read_wall_material(r, scene, b.wall_material);
  if (r.has("insert_material")) b.insert_material = r.material("insert_material", scene);
  b.normal_stress = r.number("normal_stress", b.normal_stress);
  b.shear_speed = r.number("shear_speed", b.shear_speed);
  b.inertial_number = r.number("inertial_number", b.inertial_number);
  b.shear_displacement = r.number("shear_displacement", b.shear_displacement);
  b.loading = r.choice("loading", ShearBox::Loading::DeadWeight);
  b.platen_mass = r.number("platen_mass", b.platen_mass);
  b.servo_gain = r.number("servo_gain", b.servo_gain);
  b.servo_max_speed = r.number("servo_max_speed", b.servo_max_speed);
  b.servo_integral_time = r.number("servo_integral_time", b.servo_integral_time);
  b.upper_half = r.choice("upper_half", ShearBox::UpperHalf::Fixed);
  b.upper_half_weight = r.number("upper_half_weight", b.upper_half_weight);
  b.cap = r.choice("cap", ShearBox::Cap::Held);
  b.settle_time = r.number("settle_time", b.settle_time);
  b.consolidate_time = r.number("consolidate_time", b.consolidate_time);
  const std::int64_t rows = r.optional_integer("rows").value_or(b.rows);
  if (rows < 10 || rows > 1000000)
    r.fail("out_of_range", "rows",
           std::to_string(rows) + " is out of range, allowed [10, 1000000]");
  b.rows = static_cast<int>(rows);

  b.specimen = read_specimen(r, scene);
  scene.apparatus = b;
}

// Its resolved values (scene_tables.h: the walls are rebuilt from them).
void write_shear_box(TableWriter& w) {
  const ShearBox& b = *w.scene().apparatus_as<ShearBox>();
  w.header("[shear_box]");
  w.line("length", b.length);
  w.line("width", b.width);
  w.line("split_height", b.split_height);
  w.line("gap", b.gap);
  w.material("wall_material", b.wall_material, "shear_box.wall_material");
  if (b.insert_material >= 0 && b.insert_material != b.wall_material)
    w.material("insert_material", b.insert_material, "shear_box.insert_material");
  w.line("normal_stress", b.normal_stress);
  w.line("shear_speed", b.shear_speed);
  w.line("inertial_number", b.inertial_number);
  w.line("shear_displacement", b.shear_displacement);
  w.text("loading", choice_name(b.loading));
  w.line("platen_mass", b.platen_mass);
  w.line("servo_gain", b.servo_gain);
  w.line("servo_max_speed", b.servo_max_speed);
  w.line("servo_integral_time", b.servo_integral_time);
  if (b.upper_half != ShearBox::UpperHalf::Fixed) {  // older scenes stay as they were
    w.text("upper_half", choice_name(b.upper_half));
    w.line("upper_half_weight", b.upper_half_weight);
  }
  if (b.cap != ShearBox::Cap::Held) w.text("cap", choice_name(b.cap));
  w.line("settle_time", b.settle_time);
  w.line("consolidate_time", b.consolidate_time);
  w.line("rows", std::to_string(b.rows));
  w.given_specimen("shear_box", b.specimen.preparation);
}

}  // namespace simsols::scene_toml
