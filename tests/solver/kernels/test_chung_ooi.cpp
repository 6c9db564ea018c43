// The eight impact benchmarks of Chung & Ooi (2011, Granular Matter
// 13:643), with the materials and speeds of assets/validation/
// chung_ooi_2011.csv (as three public codes re-implement them; the
// paper's own tables could not be read), against theory:
//   1, 2  elastic normal impacts (two equal spheres; a sphere on a rigid
//         plane): Hertz's largest overlap and contact time;
//   3     normal impacts with damping: the restitution given;
//   4-8   oblique impacts (a sphere on a plane at a constant speed and a
//         sweep of angles; at a constant normal speed and a sweep of
//         tangential speeds; of spins; two equal spheres with spins; two
//         spheres of different sizes): where the contact slides throughout,
//         rigid-body impulse theory (J_n = (1 + e) m* v_n, J_t = mu J_n
//         against the contact point's slip; Brach 1991, ch. 3) gives every
//         body's rebound velocity and spin. Where it sticks for a while, the
//         rebound depends on the tangential stiffness and is reported only.
// docs/validation.md, section 5, tabulates what these print.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "render/plot/chart.h"
#include "solver/common/number_text.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

constexpr double kPi = std::numbers::pi;

struct Row {
  int test = 0;
  std::string body, material;
  double radius = 0, young = 0, poisson = 0, density = 0, friction = 0, speed = 0;
  std::vector<double> restitution;
};

// The rows of the shipped CSV ('#' lines are its citation).
std::vector<Row> chung_ooi_rows() {
  std::ifstream in(std::string(SIMSOLS_SOURCE_DIR) + "/assets/validation/chung_ooi_2011.csv");
  std::vector<Row> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) { header = false; continue; }
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string c; f.size() < 10 && std::getline(ss, c, ',');) f.push_back(c);
    const auto num = [&](int i) { return f[i].empty() ? 0.0 : std::stod(f[i]); };
    Row r;
    r.test = std::stoi(f[0]);
    r.body = f[1];
    r.material = f[2];
    r.radius = num(3), r.young = num(4), r.poisson = num(5), r.density = num(6);
    std::stringstream es(f[7]);
    for (double e; es >> e;) r.restitution.push_back(e);
    r.friction = num(8), r.speed = num(9);
    rows.push_back(r);
  }
  return rows;
}

std::vector<Row> rows_of(int test, const std::string& body = "sphere") {
  std::vector<Row> out;
  for (const Row& r : chung_ooi_rows())
    if (r.test == test && r.body == body) out.push_back(r);
  EXPECT_FALSE(out.empty()) << "test " << test << " " << body << " in chung_ooi_2011.csv";
  return out;
}

Material material_of(const Row& r, double e) {
  Material m;
  m.name = r.material;
  m.young_modulus = r.young;
  m.poisson_ratio = r.poisson;
  m.density = r.density;
  m.restitution = e;
  m.sliding_friction = r.friction;
  m.rolling_friction = 0;
  return m;
}

// A plane of `plane`'s material: the pair's restitution and friction the
// sphere row's (the pair takes the mean e and the smaller mu).
Material plane_material(const Row& plane, const Row& sphere_row, double e) {
  Material m = material_of(plane, e);
  m.sliding_friction = sphere_row.friction;
  return m;
}

// A rigid plane: the sphere's material 10^4 times stiffer (E* within 10^-4
// of the sphere's own E / (1 - nu^2)); e and mu mix as the pair's.
Material rigid_of(const Material& sphere) {
  Material m = sphere;
  m.name = "rigid";
  m.young_modulus *= 1e4;
  return m;
}

// A body's state after an impact: velocity, spin.
struct Body {
  Vec3 v, w;
};

// Rigid-body impulse theory of a sliding impact along n (from body 1 to
// body 2), of radii R1, R2 and lever arms r1, r2; body 2 absent (a plane)
// when m2 = 0. `slides` is false when
// the contact point's slip would stop (or turn) before the end.
struct Impulse {
  Body b1, b2;
  bool slides = false;
};

// a + s b (solver/common/vec3.h has the rest)
Vec3 add(Vec3 a, Vec3 b, double s = 1) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }

// The law applies F_t at R - delta/2 from each centre (docs/model.md):
// over a Hertz impact the force-weighted mean overlap is
// B(7/5, 1/2)/2 = 0.8176 of the largest, so each lever arm is taken as
// R - 0.4088 delta_max (r1, r2 below are these arms).
double mean_half_overlap(double mstar, double rstar, double estar, double vn) {
  const double largest = std::pow(15 * mstar * vn * vn / (16 * estar * std::sqrt(rstar)), 0.4);
  return 0.25 * std::beta(1.4, 0.5) * largest;
}

Impulse sliding_theory(Body b1, double m1, double R1, double r1, Body b2, double m2, double R2,
                       double r2, Vec3 n, double e, double mu) {
  const double inv1 = 1 / m1, inv2 = m2 > 0 ? 1 / m2 : 0;
  const double i1 = 0.4 * m1 * R1 * R1, i2 = 0.4 * m2 * R2 * R2;
  const Vec3 u = add(add(b1.v, cross(b1.w, {r1 * n[0], r1 * n[1], r1 * n[2]})),
                     add(b2.v, cross(b2.w, {-r2 * n[0], -r2 * n[1], -r2 * n[2]})), -1);
  const double un = dot(u, n);
  const Vec3 ut = add(u, n, -un);
  const double slip = norm(ut);
  const double jn = (1 + e) * un / (inv1 + inv2), jt = mu * jn;
  const Vec3 t = slip > 0 ? Vec3{ut[0] / slip, ut[1] / slip, ut[2] / slip} : Vec3{};
  const Vec3 p = add(Vec3{jn * n[0], jn * n[1], jn * n[2]}, t, jt);  // the impulse on body 2
  Impulse out;
  out.b1 = {add(b1.v, p, -inv1), add(b1.w, cross({r1 * n[0], r1 * n[1], r1 * n[2]}, p), -1 / i1)};
  out.b2 = b2;
  if (m2 > 0)
    out.b2 = {add(b2.v, p, inv2), add(b2.w, cross({-r2 * n[0], -r2 * n[1], -r2 * n[2]}, p), 1 / i2)};
  // the slip falls linearly with the normal impulse, by 7/2 mu J_n (1/m1 + 1/m2)
  out.slides = slip > 1.05 * jt * (inv1 + r1 * r1 / i1 + inv2 + (m2 > 0 ? r2 * r2 / i2 : 0));
  return out;
}

// Runs the scene's one or two spheres through their contact; the bodies after.
std::vector<Body> impact(const Scene& s) {
  Simulation sim(default_device(), s);
  EXPECT_TRUE(advance_through_contact(sim, 0, 2000000)) << "contact never ended";
  const ParticleSnapshot q = sim.snapshot();
  std::vector<Body> out;
  for (size_t i = 0; i < s.particles.size(); ++i) out.push_back({q.velocity[i], q.angular_velocity[i]});
  return out;
}

// The scene of a sphere of `row` (restitution e) hitting a rigid plane z = 0
// with velocity v and spin w, from 10^-6 R above it.
Scene sphere_on_plane(Precision p, const Row& row, double e, Vec3 v, Vec3 w,
                      const Material* plane_material = nullptr) {
  const Material m = material_of(row, e);
  Scene s = empty_scene(p, m);
  s.materials.push_back(plane_material ? *plane_material : rigid_of(m));
  s.particles = {sphere(row.radius, {0, 0, row.radius * (1 + 1e-6)}, v, w)};
  s.walls = {plane("plane", {0, 0, 0}, {0, 0, 1})};
  s.walls[0].material = 1;
  return s;
}

double sphere_mass(const Row& r) { return r.density * 4.0 / 3.0 * kPi * std::pow(r.radius, 3); }

// measured change / theory's change, per component that changes by more
// than 1e-9 of the scale; the worst |ratio - 1| over both bodies.
double worst_change_error(const std::vector<Body>& before, const std::vector<Body>& after,
                          const Impulse& theory, double v_scale, double w_scale) {
  double worst = 0;
  const Body expected[2] = {theory.b1, theory.b2};
  for (size_t b = 0; b < after.size(); ++b)
    for (int k = 0; k < 3; ++k) {
      const double dv = expected[b].v[k] - before[b].v[k], dw = expected[b].w[k] - before[b].w[k];
      if (std::fabs(dv) > 1e-6 * v_scale)
        worst = std::max(worst, std::fabs((after[b].v[k] - before[b].v[k]) / dv - 1));
      if (std::fabs(dw) > 1e-6 * w_scale)
        worst = std::max(worst, std::fabs((after[b].w[k] - before[b].w[k]) / dw - 1));
    }
  return worst;
}

// Hertz's largest overlap and contact time of a normal impact at closing
// speed v (Johnson 1985, section 11.1): delta = (15 m* v^2 / (16 E* R*^1/2))^2/5,
// t_c = 2.9432 delta / v.
struct Hertz {
  double overlap, time;
};
Hertz hertz(double mstar, double rstar, double estar, double v) {
  const double d = std::pow(15 * mstar * v * v / (16 * estar * std::sqrt(rstar)), 0.4);
  return {d, 2.9432 * d / v};
}

// Steps a normal impact along z, sampling the gap between the bodies every
// step: the largest overlap, and the time in contact with its start and end
// interpolated within their steps.
Hertz measure_normal(const Scene& s) {
  Simulation sim(default_device(), s);
  const double dt = sim.dt();
  const auto overlap_now = [&] {
    const ParticleSnapshot q = sim.snapshot();
    return s.particles.size() == 2
               ? s.particles[0].radius + s.particles[1].radius - (q.position[1][2] - q.position[0][2])
               : s.particles[0].radius - q.position[0][2];
  };
  double worst = 0, t = 0, start = -1, before = overlap_now();
  for (int k = 0; k < 2000000; ++k) {
    sim.advance(1);
    t += dt;
    const double d = overlap_now();
    const double crossing = t - dt * d / (d - before);  // where the gap passed 0
    if (start < 0 && d > 0) start = crossing;
    worst = std::max(worst, d);
    if (start >= 0 && d <= 0) return {worst, crossing - start};
    before = d;
  }
  ADD_FAILURE() << "contact never ended";
  return {worst, 0};
}

class ChungOoi : public PrecisionTest {};

// Test 1: two equal spheres head-on at 10 m/s each, elastic.
TEST_P(ChungOoi, Test1TwoEqualSpheresHertz) {
  for (const Row& r : rows_of(1)) {
    Scene s = empty_scene(GetParam(), material_of(r, 1.0));
    const double gap = 1e-6 * r.radius;
    s.particles = {sphere(r.radius, {0, 0, 0}, {0, 0, r.speed}),
                   sphere(r.radius, {0, 0, 2 * r.radius + gap}, {0, 0, -r.speed})};
    const double estar = r.young / (2 * (1 - r.poisson * r.poisson));
    const Hertz h = hertz(sphere_mass(r) / 2, r.radius / 2, estar, 2 * r.speed);
    const Hertz m = measure_normal(s);
    report("test 1 largest overlap (" + r.material + ")", m.overlap, h.overlap);
    report("test 1 contact time (" + r.material + ")", m.time, h.time);
    EXPECT_NEAR(m.overlap / h.overlap, 1, 0.012) << r.material;
    EXPECT_NEAR(m.time / h.time, 1, 0.015) << r.material;
  }
}

// Test 2: a sphere on a rigid plane at 0.2 m/s, elastic.
TEST_P(ChungOoi, Test2SphereOnARigidPlaneHertz) {
  for (const Row& r : rows_of(2)) {
    const Scene s = sphere_on_plane(GetParam(), r, 1.0, {0, 0, -r.speed}, {});
    const double estar = 1 / ((1 - r.poisson * r.poisson) / r.young +
                              (1 - r.poisson * r.poisson) / (1e4 * r.young));
    const Hertz h = hertz(sphere_mass(r), r.radius, estar, r.speed);
    const Hertz m = measure_normal(s);
    report("test 2 largest overlap (" + r.material + ")", m.overlap, h.overlap);
    report("test 2 contact time (" + r.material + ")", m.time, h.time);
    EXPECT_NEAR(m.overlap / h.overlap, 1, 0.002) << r.material;
    EXPECT_NEAR(m.time / h.time, 1, 0.003) << r.material;
  }
}

// Test 3: an aluminium oxide sphere on a cast iron plane at 3.9 m/s, the
// restitution given from 0.2 to 1.
TEST_P(ChungOoi, Test3RestitutionAsGiven) {
  const Row r = rows_of(3)[0];
  const Row plane_row = rows_of(3, "plane")[0];
  for (double e : r.restitution) {
    const Material plane_m = plane_material(plane_row, r, e);
    const Scene s = sphere_on_plane(GetParam(), r, e, {0, 0, -r.speed}, {}, &plane_m);
    const std::vector<Body> after = impact(s);
    report("test 3 restitution (e = " + shortest_number(e) + ")", after[0].v[2] / r.speed, e);
    EXPECT_NEAR(after[0].v[2] / r.speed / e, 1, 0.001) << "e = " << e;
  }
}

// One sweep's figure, like the paper's: the measured quantity (markers)
// and the sliding theory (a line, where the contact slides throughout),
// per material. With SIMSOLS_FIGURES_DIR set, written there as
// <file>.png and <file>.csv when the sweep ends (docs/validation.md's
// figures: SIMSOLS_FIGURES_DIR=docs/img build/release/tests/test_chung_ooi
// --gtest_filter='*/double').
class Sweep {
 public:
  Sweep(std::string file, std::string title, std::string x_label, std::string y_label)
      : file_(std::move(file)) {
    chart_.title = std::move(title);
    chart_.x_label = std::move(x_label);
    chart_.y_label = std::move(y_label);
  }
  // theory_line false: the line's theory is another line's (drawn once)
  void add(const std::string& material, double x, double measured, const Impulse& th, double theory,
           bool theory_line = true) {
    Line& l = lines_[material];
    l.measured.label = material + ", SimSols";
    l.measured.line = false;
    l.measured.markers = true;
    l.measured.x.push_back(x);
    l.measured.y.push_back(measured);
    l.theory.label = material + ", sliding theory";
    l.theory.dashed = true;
    if (th.slides && theory_line) l.theory.x.push_back(x), l.theory.y.push_back(theory);
    csv_ += material + "," + shortest_number(x) + "," + shortest_number(measured) + "," +
            (th.slides ? shortest_number(theory) : std::string()) + "\n";
  }
  ~Sweep() {
    const char* dir = std::getenv("SIMSOLS_FIGURES_DIR");
    if (!dir || ::testing::Test::HasFailure()) return;
    for (auto& [material, l] : lines_) {
      chart_.series.push_back(l.measured);
      if (!l.theory.x.empty()) chart_.series.push_back(l.theory);
    }
    const std::string base = std::string(dir) + "/" + file_;
    plot::write_chart_png(chart_, base + ".png");
    std::ofstream(base + ".csv") << "# " << chart_.title << " (tests/solver/kernels/test_chung_ooi.cpp)\n"
                                 << "material," << chart_.x_label << "," << chart_.y_label
                                 << ",sliding theory (empty: sticks for a while)\n" << csv_;
  }

 private:
  struct Line {
    plot::Series measured, theory;
  };
  std::string file_, csv_;
  plot::Chart chart_;
  std::map<std::string, Line> lines_;
};

// Coulomb in impulse form, sliding or not: body 1's change of velocity
// across n (from body 1 to its partner) is at most mu times its change
// against n.
void expect_coulomb(const Body& before, const Body& after, Vec3 n, double mu,
                    const std::string& label) {
  const Vec3 dv = sub(after.v, before.v);
  const double dn = -dot(dv, n);
  EXPECT_LE(norm(add(dv, n, dn)), mu * dn * (1 + 1e-3)) << label;
}

// What one impact gave: the bodies after, the sliding theory, and the
// worst error of the changes against it (-1 when it does not slide
// throughout: then only printed).
struct Outcome {
  std::vector<Body> after;
  Impulse theory;
  double error = -1;
};

Outcome oblique_on_plane(const Scene& s, const Row& r, double e, const std::string& label) {
  const Particle& p = s.particles[0];
  const std::vector<Body> before = {{p.velocity, p.angular_velocity}};
  Outcome o;
  o.after = impact(s);
  const Material &a = s.materials[0], &b = s.materials[1];
  const double estar = 1 / ((1 - a.poisson_ratio * a.poisson_ratio) / a.young_modulus +
                            (1 - b.poisson_ratio * b.poisson_ratio) / b.young_modulus);
  const double m = sphere_mass(r);
  const double arm = r.radius - mean_half_overlap(m, r.radius, estar, -p.velocity[2]);
  o.theory = sliding_theory(before[0], m, r.radius, arm, {}, 0, 0, 0, {0, 0, -1}, e, r.friction);
  const Impulse& th = o.theory;
  const double vt = o.after[0].v[0], vn = o.after[0].v[2], wr = o.after[0].w[1] * r.radius;
  std::printf("[measure] %s: v_t' = %.6g m/s (theory %.6g), w'R = %.6g m/s (theory %.6g), "
              "v_n' = %.6g m/s%s\n", label.c_str(), vt, th.b1.v[0], wr, th.b1.w[1] * r.radius, vn,
              th.slides ? "" : " (sticks for a while: no theory)");
  expect_coulomb(before[0], o.after[0], {0, 0, -1}, r.friction, label);
  const double speed = norm(p.velocity);
  if (th.slides) o.error = worst_change_error(before, o.after, th, speed, speed / r.radius);
  return o;
}

// The worst error over a sweep's sliding cases, and how many there were.
struct Worst {
  double error = 0;
  int sliding = 0;
  void add(const Outcome& o) {
    if (o.error >= 0) error = std::max(error, o.error), ++sliding;
  }
  void print(const char* test) const {
    std::printf("[measure] %s: %d sliding cases, worst change error %.4f%%\n", test, sliding,
                100 * error);
  }
};

// Test 4: 3.9 m/s at 5 to 85 degrees from the normal: the tangential
// restitution v_t'/v_t and the rebound spin, with the linear spring
// (tangential = mindlin) and with micro-slip (mindlin_deresiewicz): the
// two agree with the sliding theory where the contact slides throughout
// and differ where it sticks for a while (printed and drawn, no
// reference values there).
TEST_P(ChungOoi, Test4ConstantSpeedSweepOfAngles) {
  const Row r = rows_of(4)[0];
  const Material plane_m = plane_material(rows_of(4, "plane")[0], r, r.restitution[0]);
  Sweep et("chung_ooi_test4_restitution", "Chung & Ooi test 4: tangential restitution",
           "impact angle (deg)", "v_t' / v_t");
  Sweep spin("chung_ooi_test4_spin", "Chung & Ooi test 4: rebound spin", "impact angle (deg)",
             "w' (rad/s)");
  for (const TangentialModel law : {TangentialModel::Mindlin, TangentialModel::MindlinDeresiewicz}) {
    const bool micro = law == TangentialModel::MindlinDeresiewicz;
    const std::string line = micro ? r.material + ", micro-slip" : r.material;
    Worst worst;
    for (int deg = 5; deg <= 85; deg += 5) {
      const double a = deg * kPi / 180, e = r.restitution[0], vt = r.speed * std::sin(a);
      Scene s = sphere_on_plane(GetParam(), r, e, {vt, 0, -r.speed * std::cos(a)}, {}, &plane_m);
      s.effects.tangential = law;
      const Outcome o = oblique_on_plane(s, r, e, "test 4 (" + line + ") at " + std::to_string(deg) + " deg");
      worst.add(o);
      et.add(line, deg, o.after[0].v[0] / vt, o.theory, o.theory.b1.v[0] / vt, !micro);
      spin.add(line, deg, o.after[0].w[1], o.theory, o.theory.b1.w[1], !micro);
    }
    worst.print(micro ? "test 4, micro-slip" : "test 4");
    EXPECT_GE(worst.sliding, 10);
    EXPECT_LT(worst.error, 0.0004);  // ten times the largest error measured
  }
}

// Test 5: v_n = 5 m/s, tangential speeds psi mu v_n, psi = 1 ... 20: the
// normalised rebound spin R w' / (mu v_n).
TEST_P(ChungOoi, Test5ConstantNormalSpeedSweepOfTangentialSpeeds) {
  Sweep fig("chung_ooi_test5_spin", "Chung & Ooi test 5: normalised rebound spin",
            "v_t / (mu v_n)", "R w' / (mu v_n)");
  Worst worst;
  for (const Row& r : rows_of(5))
    for (double psi : {1.0, 2.0, 4.0, 6.0, 8.0, 10.0, 14.0, 20.0}) {
      const double e = r.restitution[0], scale = r.radius / (r.friction * r.speed);
      const Scene s = sphere_on_plane(GetParam(), r, e, {psi * r.friction * r.speed, 0, -r.speed}, {});
      const Outcome o = oblique_on_plane(s, r, e, "test 5 " + r.material + " psi " + shortest_number(psi));
      worst.add(o);
      fig.add(r.material, psi, o.after[0].w[1] * scale, o.theory, o.theory.b1.w[1] * scale);
    }
  worst.print("test 5");
  EXPECT_GE(worst.sliding, 6);
  EXPECT_LT(worst.error, 0.004);  // ten times the largest error measured
}

// Test 6: v_n = 0.2 m/s, no tangential speed, spins whose contact point
// moves at V_ct = k v_n, k = 0.5 ... 16: beta = -V_ct'/V_ct against
// 7/2 mu (1 + e) v_n / V_ct (the sliding theory: beta = x - 1).
TEST_P(ChungOoi, Test6ConstantNormalSpeedSweepOfSpins) {
  Sweep fig("chung_ooi_test6_beta", "Chung & Ooi test 6: contact point's rebound",
            "7/2 mu (1 + e) v_n / V_ct", "beta = -V_ct' / V_ct");
  Worst worst;
  for (const Row& r : rows_of(6))
    for (double k : {0.5, 1.0, 2.0, 4.0, 8.0, 16.0}) {
      const double e = r.restitution[0], vct = k * r.speed;
      // a spin about -y moves the contact point (at -R z) along +x
      const Scene s = sphere_on_plane(GetParam(), r, e, {0, 0, -r.speed}, {0, -vct / r.radius, 0});
      const Outcome o = oblique_on_plane(s, r, e, "test 6 " + r.material + " V_ct/v_n " + shortest_number(k));
      worst.add(o);
      const auto beta = [&](const Body& b) { return -(b.v[0] - r.radius * b.w[1]) / vct; };
      fig.add(r.material, 3.5 * r.friction * (1 + e) / k, beta(o.after[0]), o.theory, beta(o.theory.b1));
    }
  worst.print("test 6");
  EXPECT_GE(worst.sliding, 6);
  EXPECT_LT(worst.error, 0.001);  // ten times the largest error measured
}

// Two spheres (radii r1, r2 = ratio r1) closing along z: sphere 1 at
// +v_n with spin w1, sphere 2 at -v2 with spin w2.
Outcome two_spheres(Precision p, const Row& r, double ratio, double v2, Vec3 w1, Vec3 w2,
                    const std::string& label) {
  const double e = r.restitution[0], r2 = ratio * r.radius;
  Scene s = empty_scene(p, material_of(r, e));
  s.particles = {sphere(r.radius, {0, 0, 0}, {0, 0, r.speed}, w1),
                 sphere(r2, {0, 0, r.radius + r2 + 1e-6 * r.radius}, {0, 0, -v2}, w2)};
  const std::vector<Body> before = {{s.particles[0].velocity, w1}, {s.particles[1].velocity, w2}};
  Outcome o;
  o.after = impact(s);
  const double m1 = sphere_mass(r), m2 = m1 * ratio * ratio * ratio;
  const double half = mean_half_overlap(m1 * m2 / (m1 + m2), r.radius * r2 / (r.radius + r2),
                                        r.young / (2 * (1 - r.poisson * r.poisson)), r.speed + v2);
  o.theory = sliding_theory(before[0], m1, r.radius, r.radius - half, before[1], m2, r2, r2 - half,
                            {0, 0, 1}, e, r.friction);
  const Impulse& th = o.theory;
  const std::vector<Body>& after = o.after;
  std::printf("[measure] %s: sphere 1 v_t' = %.6g (theory %.6g), w' = %.6g (%.6g); sphere 2 "
              "v_t' = %.6g (%.6g), w' = %.6g (%.6g)%s\n", label.c_str(), after[0].v[0],
              th.b1.v[0], after[0].w[1], th.b1.w[1], after[1].v[0], th.b2.v[0], after[1].w[1],
              th.b2.w[1], th.slides ? "" : " (sticks for a while: no theory)");
  expect_coulomb(before[0], after[0], {0, 0, 1}, r.friction, label);
  if (th.slides) o.error = worst_change_error(before, after, th, r.speed, r.speed / r.radius);
  return o;
}

// Tests 7 and 8: sphere 1 of test `test`'s rows at 0.2 m/s with spin w0
// about y, w0 = 0.5 ... 22 rad/s, onto sphere 2 of `ratio` times its radius
// closing at v2 (with the same spin when `both_spin`): sphere 1's rebound
// spin, drawn into `fig`; the worst error over the sliding cases.
Worst spin_sweep(Precision p, int test, double ratio, bool both_spin, double v2_of_speed,
                 Sweep& fig) {
  Worst worst;
  for (const Row& r : rows_of(test))
    for (double w0 : {0.5, 1.0, 2.0, 5.0, 10.0, 22.0}) {
      const Vec3 w{0, w0, 0};
      const Outcome o = two_spheres(p, r, ratio, v2_of_speed * r.speed, w, both_spin ? w : Vec3{},
                                    "test " + std::to_string(test) + " " + r.material + " w0 " +
                                        shortest_number(w0));
      worst.add(o);
      fig.add(r.material, w0, o.after[0].w[1], o.theory, o.theory.b1.w[1]);
    }
  worst.print(("test " + std::to_string(test)).c_str());
  return worst;
}

// Test 7: two equal spheres at +-0.2 m/s, both spinning at w0 about y (their
// contact points slip at 2 w0 R).
TEST_P(ChungOoi, Test7TwoEqualSpheresSweepOfSpins) {
  Sweep fig("chung_ooi_test7_spin", "Chung & Ooi test 7: two equal spheres, rebound spin",
            "w0 (rad/s)", "w' (rad/s)");
  const Worst worst = spin_sweep(GetParam(), 7, 1, true, 1, fig);
  EXPECT_GE(worst.sliding, 6);
  EXPECT_LT(worst.error, 0.003);  // ten times the largest error measured
}

// Test 8: a spinning sphere at 0.2 m/s onto a sphere of 5 times its radius
// at rest.
TEST_P(ChungOoi, Test8SpheresOfDifferentSizesSweepOfSpins) {
  Sweep fig("chung_ooi_test8_spin", "Chung & Ooi test 8: spheres of radii 1:5, rebound spin",
            "w0 (rad/s)", "w' (rad/s)");
  const Worst worst = spin_sweep(GetParam(), 8, 5, false, 0, fig);
  EXPECT_GE(worst.sliding, 6);
  EXPECT_LT(worst.error, 0.002);  // ten times the largest error measured
}

SIMSOLS_BOTH_PRECISIONS(ChungOoi);

}  // namespace
}  // namespace simsols::testing
