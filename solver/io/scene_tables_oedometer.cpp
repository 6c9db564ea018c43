// [oedometer]: one-dimensional compression in a rigid square ring
// (docs/oedometer.md), expanded into walls and beads by build_oedometer() (registry.h).
#include "solver/io/scene_tables.h"

namespace simsols::scene_toml {

void read_oedometer(const Reader& root, Scene& scene) {
  Reader r = root.sub("oedometer", {"length", "width", "wall_material", "load_steps", "step_time",
                                    "settle_time", "servo_gain", "servo_max_speed",
                                    "servo_integral_time", "friction_angle", "specimen"});
  Oedometer o;
  o.length = r.number("length", o.length);
  o.width = r.number("width", o.width);
  o.wall_material = read_wall_material(r, scene, o.wall_material);
  o.load_steps = r.numbers("load_steps", o.load_steps);
  o.step_time = r.number("step_time", o.step_time);
  o.settle_time = r.number("settle_time", o.settle_time);
  o.servo_gain = r.number("servo_gain", o.servo_gain);
  o.servo_max_speed = r.number("servo_max_speed", o.servo_max_speed);
  o.servo_integral_time = r.number("servo_integral_time", o.servo_integral_time);
  o.friction_angle = r.number("friction_angle", o.friction_angle);
  o.specimen = read_specimen(r, scene);
  scene.apparatus = o;
}

// Its resolved values (scene_tables.h: the walls are rebuilt from them).
void write_oedometer(TableWriter& w) {
  const Oedometer& o = *w.scene().apparatus_as<Oedometer>();
  w.header("[oedometer]");
  w.line("length", o.length);
  w.line("width", o.width);
  w.material("wall_material", o.wall_material, "oedometer.wall_material");
  w.line("load_steps", o.load_steps);
  w.line("step_time", o.step_time);
  w.line("settle_time", o.settle_time);
  w.line("servo_gain", o.servo_gain);
  w.line("servo_max_speed", o.servo_max_speed);
  w.line("servo_integral_time", o.servo_integral_time);
  w.line("friction_angle", o.friction_angle);
  w.given_specimen("oedometer", o.specimen.preparation);
}

}  // namespace simsols::scene_toml
