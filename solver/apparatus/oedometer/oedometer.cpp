#include "solver/apparatus/oedometer/oedometer.h"

#include <algorithm>
#include <cmath>

#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/specimen/specimen.h"

namespace simsols {
namespace {

const TableCheck kCheck{"oedometer"};

void check_fields(const Oedometer& o, const Scene& scene) {
  kCheck.require(o.length > 0 && o.length < 10, "length", o.length, "(0, 10) m");
  kCheck.require(o.width > 0 && o.width < 10, "width", o.width, "(0, 10) m");
  if (o.load_steps.size() < 2 || o.load_steps.size() > 100)
    kCheck.fail("out_of_range", "load_steps",
                std::to_string(o.load_steps.size()) + " steps; allowed 2 to 100 stresses");
  for (size_t i = 0; i < o.load_steps.size(); ++i)
    kCheck.require(o.load_steps[i] > 0 && o.load_steps[i] <= 1e9,
                   "load_steps[" + std::to_string(i) + "]", o.load_steps[i], "(0, 1e9] Pa");
  kCheck.require(o.step_time > 0 && o.step_time <= 100, "step_time", o.step_time, "(0, 100] s");
  kCheck.require(o.settle_time >= 0 && o.settle_time <= 100, "settle_time", o.settle_time,
                 "[0, 100] s");
  check_servo_settings(kCheck, o.servo_gain, o.servo_max_speed, o.servo_integral_time);
  kCheck.require(o.friction_angle >= 0 && o.friction_angle < 90, "friction_angle",
                 o.friction_angle, "[0, 90) deg (0 = none given)");
  check_wall_room(scene, kOedometerWalls, kCheck, "oedometer");
}

void add_walls(Scene& scene, Oedometer& o, double top, double r_max) {
  const int m = o.wall_material;
  const double L = o.length, W = o.width;
  const double platen_z = top + 0.2 * r_max;
  const double h = platen_z + 4 * r_max;  // the sides' height
  o.first_wall = static_cast<int>(scene.walls.size());
  std::vector<Wall> w = cuboid_walls("ring", m, L, W, h, platen_z, 0);
  // The platen's servo, switched on and tuned by the loading programme
  // (oedometer_programme.h).
  WallServo& servo = w[kOedPlaten].servo;
  servo.enabled = true;
  servo.target_force = o.load_steps.front() * oedometer_area(o);
  servo.gain = 1;
  servo.max_speed = o.servo_max_speed;
  scene.walls.insert(scene.walls.end(), w.begin(), w.end());
}

void build(Scene& scene) {
  Oedometer& o = *scene.apparatus_as<Oedometer>();
  check_fields(o, scene);
  if (auto issue = place_specimen(scene, o.specimen, o.length, o.width, "oedometer"))
    throw TableProblem{*issue};
  const SpecimenExtent e = measure_cell_specimen(scene, o.length, o.width, kCheck, "ring");
  if (!resolve_wall_material(scene, o.wall_material))
    kCheck.fail("unknown_material", "wall_material", "the ring's material does not exist");
  add_walls(scene, o, e.top, e.r_max);
}

}  // namespace

std::optional<SceneIssue> build_oedometer(Scene& scene) {
  if (!scene.apparatus_as<Oedometer>()) return std::nullopt;
  try {
    build(scene);
  } catch (const TableProblem& p) {
    return p.issue;
  }
  return std::nullopt;
}

double oedometer_area(const Oedometer& o) { return o.length * o.width; }

int oedometer_peak_step(const Oedometer& o) {
  const auto& s = o.load_steps;
  return static_cast<int>(std::max_element(s.begin(), s.end()) - s.begin());
}


double oedometer_expected_time(const Scene& s) {
  const Oedometer& o = *s.apparatus_as<Oedometer>();
  return 0.3 * (o.settle_time + double(o.load_steps.size()) * o.step_time);
}
}  // namespace simsols
