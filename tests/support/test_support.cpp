#include "tests/support/test_support.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>

#include "solver/common/errors.h"
#include "solver/core/engine_options.h"
#include "solver/core/observe.h"
#include "solver/io/scene_toml.h"

namespace simsols {

std::shared_ptr<Device> default_device() {
  static std::once_flag once;
  static std::shared_ptr<Device> device;
  std::call_once(once, [] { device = Device::open(engine_options_from_environment()); });
  return device;
}

}  // namespace simsols

namespace simsols::testing {

ScopedVariable::ScopedVariable(const char* name, const char* value) : name_(name) {
  if (const char* old = std::getenv(name)) old_ = old, had_ = true;
  if (value != nullptr) ::setenv(name, value, 1);
  else ::unsetenv(name);
}

ScopedVariable::~ScopedVariable() {
  if (had_) ::setenv(name_, old_.c_str(), 1);
  else ::unsetenv(name_);
}

void report(const std::string& what, double measured, double theory) {
  const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
  std::printf("[measure] %s.%s %s: measured %.6g, theory %.6g, error %+.3f%%\n",
              t ? t->test_suite_name() : "", t ? t->name() : "", what.c_str(), measured, theory,
              theory != 0 ? 100.0 * (measured / theory - 1.0) : 0.0);
}

Scene small_shear_box(const std::string& name, double sigma, double displacement, Precision p,
                      Specimen::Method method) {
  const double d = 6.35e-3;
  Scene s;
  s.name = name;
  s.materials.push_back(paper_glass());
  s.numerics.precision = p;
  s.numerics.duration = 1;
  ShearBox b;
  b.length = 5.27 * d;
  b.width = 5.26 * d;
  b.normal_stress = sigma;
  b.shear_displacement = displacement;
  b.rows = 100;
  b.settle_time = method == Specimen::Method::Pour ? 0.1 : 0.005;
  b.specimen.material = 0;
  b.specimen.diameter = d;
  b.specimen.layers = 4;
  b.specimen.seed = 5;
  b.specimen.method = method;
  s.apparatus = b;
  if (auto issue = build_shear_box(s)) ADD_FAILURE() << issue->field << ": " << issue->message;
  return s;
}

bool all_finite(const ParticleSnapshot& q) {
  for (size_t i = 0; i < q.position.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(q.position[i][c]) || !std::isfinite(q.velocity[i][c]) ||
          !std::isfinite(q.angular_velocity[i][c]))
        return false;
  return true;
}

bool stability_full_form() {
  const char* v = std::getenv("SIMSOLS_STABILITY_FULL");
  return v && std::atoi(v) != 0;
}

Material glass(double restitution, double mu_s, double mu_r) {
  Material m = paper_glass();
  m.restitution = restitution;
  m.sliding_friction = mu_s;
  m.rolling_friction = mu_r;
  return m;
}

Material soft(double restitution, double mu_s, double mu_r) {
  Material m;
  m.name = "soft";
  m.young_modulus = 0.5e9;
  m.poisson_ratio = 0.3;
  m.density = 1200;
  m.restitution = restitution;
  m.sliding_friction = mu_s;
  m.rolling_friction = mu_r;
  return m;
}

Scene empty_scene(Precision p, const Material& m) {
  Scene s;
  s.name = "test";
  s.materials = {m};
  s.effects.gravity = {0, 0, 0};
  s.numerics.precision = p;
  s.numerics.duration = 1;
  return s;
}

Particle sphere(double radius, Vec3 position, Vec3 velocity, Vec3 omega) {
  Particle p;
  p.radius = radius;
  p.position = position;
  p.velocity = velocity;
  p.angular_velocity = omega;
  return p;
}

Wall plane(const std::string& name, Vec3 point, Vec3 normal) {
  Wall w;
  w.name = name;
  w.shape = WallShape::Plane;
  w.point = point;
  w.normal = normal;
  return w;
}

Scene tilting_cap_scene(Precision p, double r_left, double r_right, bool dead_weight) {
  Scene s = empty_scene(p, soft(0.5, 0.3, 0.0));
  s.effects.gravity = {0, 0, -9.81};
  const double a = 10e-3, top = 2 * std::max(r_left, r_right);
  s.particles = {sphere(r_left, {-a, 0, r_left}), sphere(r_right, {a, 0, r_right})};
  Wall cap;
  cap.name = "cap";
  cap.shape = WallShape::Rectangle;
  cap.point = {0, 0, top + 1e-4};
  cap.normal = {0, 0, -1};
  cap.axis_u = {1, 0, 0};
  cap.half_u = 15e-3;
  cap.half_v = 5e-3;
  cap.tilts = true;
  cap.servo.enabled = true;
  cap.servo.target_force = 1.0;
  if (dead_weight) {
    cap.servo.mass = 0.01;
  } else {
    cap.servo.gain = 0.015;
    cap.servo.max_speed = 0.05;
  }
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), cap};
  return s;
}

double mass(const Scene& s, const Particle& p) {
  return s.materials[p.material].density * 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius, 3);
}

double e_star(const Material& m) {
  return m.young_modulus / (2 * (1 - m.poisson_ratio * m.poisson_ratio));
}

std::string glass_toml(const std::string& sliding_friction) {
  return R"(
[[materials]]
name = "glass"
young_modulus = 62.784e9
poisson_ratio = 0.2
density = 2230
restitution = 0.87
sliding_friction = )" + sliding_friction + R"(
rolling_friction = 5e-5
)";
}

void expect_scene_error(const std::string& text, const std::string& code,
                        const std::string& field) {
  try {
    parse_scene(text, "bad.toml");
    ADD_FAILURE() << "accepted, expected " << code << " at " << field;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, code) << e.what();
    EXPECT_EQ(e.field, field) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.toml"), std::string::npos) << e.what();
  }
}

std::string triaxial_cell_toml(const std::string& materials, const std::string& triaxial_keys,
                               const std::string& precision) {
  return materials + R"(
[triaxial]
length = 34.925e-3
width = 34.925e-3
)" + triaxial_keys + R"(
[triaxial.specimen]
method = "pour"
material = "glass"
diameter = 6.35e-3
layers = 6
seed = 2

[numerics]
precision = ")" + precision + R"("
dt_fraction = 0.25
duration = 1
)";
}

double max_speed(const ParticleSnapshot& q) {
  double v = 0;
  for (const Vec3& u : q.velocity) v = std::max(v, std::sqrt(dot(u, u)));
  return v;
}

Overlaps max_overlaps(Simulation& sim, const ParticleSnapshot& q) {
  Overlaps o;
  const size_t n = q.position.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const Vec3 d = sub(q.position[i], q.position[j]);
      const double gap = std::sqrt(dot(d, d)) - q.radius[i] - q.radius[j];
      o.pair = std::max(o.pair, -gap);
    }
  const std::vector<Vec3> points = wall_points(sim.model(), sim.state());
  const std::vector<Wall>& walls = sim.scene().walls;
  for (size_t w = 0; w < walls.size(); ++w) {
    for (size_t i = 0; i < n; ++i) {
      const double dist = wall_distance(walls[w], points[w], q.position[i]);
      if (dist >= 0) o.wall = std::max(o.wall, q.radius[i] - dist);  // behind a plane: ignored
    }
  }
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace simsols::testing
