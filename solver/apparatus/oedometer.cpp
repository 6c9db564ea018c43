#include "solver/apparatus/oedometer.h"

#include <algorithm>
#include <cmath>

#include "solver/apparatus/cell_walls.h"
#include "solver/apparatus/specimen.h"
#include "solver/common/number_text.h"

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
  kCheck.require(o.servo_gain >= 0, "servo_gain", o.servo_gain,
                 "[0, inf) m/(s N) (0 = automatic)");
  kCheck.require(o.servo_max_speed > 0 && o.servo_max_speed <= 10, "servo_max_speed",
                 o.servo_max_speed, "(0, 10] m/s");
  kCheck.require(o.servo_integral_time >= 0, "servo_integral_time", o.servo_integral_time,
                 "[0, inf) s (0 = automatic)");
  kCheck.require(o.friction_angle >= 0 && o.friction_angle < 90, "friction_angle",
                 o.friction_angle, "[0, 90) deg (0 = none given)");
  if (scene.walls.size() + kOedometerWalls > kMaxWalls)
    kCheck.fail("out_of_range", "length",
                "the oedometer adds " + std::to_string(int(kOedometerWalls)) +
                    " walls to the scene's " + std::to_string(scene.walls.size()) + "; at most " +
                    std::to_string(kMaxWalls) + " walls are allowed");
}

// Every bead inside the ring; returns the height of the highest bead's top
// and the largest radius.
std::pair<double, double> check_beads(const Scene& scene, const Oedometer& o) {
  if (scene.particles.empty())
    kCheck.fail("out_of_range", "specimen.method", "the specimen has no beads (the scene lists none)");
  double top = 0, r_max = 0;
  for (const Particle& p : scene.particles) {
    const Vec3& x = p.position;
    const bool inside = x[0] >= p.radius && x[0] <= o.length - p.radius && x[1] >= p.radius &&
                        x[1] <= o.width - p.radius && x[2] >= p.radius;
    if (!inside)
      kCheck.fail("out_of_range", "specimen.method",
                  "a bead at (" + shortest_number(x[0]) + ", " + shortest_number(x[1]) + ", " +
                      shortest_number(x[2]) +
                      ") is not inside the ring [0, length] x [0, width] x [0, inf)");
    top = std::max(top, x[2] + p.radius);
    r_max = std::max(r_max, p.radius);
  }
  return {top, r_max};
}

void add_walls(Scene& scene, Oedometer& o, double top, double r_max) {
  const int m = o.wall_material;
  const double L = o.length, W = o.width;
  const double platen_z = top + 0.2 * r_max;
  const double h = platen_z + 4 * r_max;  // the sides' height
  const Vec3 ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};
  o.first_wall = static_cast<int>(scene.walls.size());
  auto& w = scene.walls;
  w.push_back(rectangle_wall("floor", m, {L / 2, W / 2, 0}, ez, ex, L / 2, W / 2));
  w.push_back(rectangle_wall("ring_x0", m, {0, W / 2, h / 2}, ex, ey, W / 2, h / 2));
  w.push_back(rectangle_wall("ring_x1", m, {L, W / 2, h / 2}, {-1, 0, 0}, ey, W / 2, h / 2));
  w.push_back(rectangle_wall("ring_y0", m, {L / 2, 0, h / 2}, ey, ex, L / 2, h / 2));
  w.push_back(rectangle_wall("ring_y1", m, {L / 2, W, h / 2}, {0, -1, 0}, ex, L / 2, h / 2));
  Wall platen = rectangle_wall("platen", m, {L / 2, W / 2, platen_z}, {0, 0, -1}, ex, L / 2, W / 2);
  // Switched on and tuned by the loading programme (oedometer_test.h).
  platen.servo.enabled = true;
  platen.servo.target_force = o.load_steps.front() * oedometer_area(o);
  platen.servo.gain = 1;
  platen.servo.max_speed = o.servo_max_speed;
  w.push_back(platen);
}

void build(Scene& scene) {
  Oedometer& o = *scene.oedometer;
  check_fields(o, scene);
  if (auto issue = place_specimen(scene, o.specimen, o.length, o.width, "oedometer"))
    throw TableProblem{*issue};
  const auto [top, r_max] = check_beads(scene, o);
  if (!resolve_wall_material(scene, o.wall_material))
    kCheck.fail("unknown_material", "wall_material", "the ring's material does not exist");
  add_walls(scene, o, top, r_max);
}

}  // namespace

std::optional<SceneIssue> build_oedometer(Scene& scene) {
  if (!scene.oedometer) return std::nullopt;
  if (scene.shear_box)
    return SceneIssue{"conflicting_keys", "oedometer",
                      "a scene holds one apparatus: [shear_box] or [oedometer], not both"};
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

}  // namespace simsols
