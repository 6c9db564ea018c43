// What a run measures (solver/core/observe.h), against the same quantities
// computed on the host from the downloaded state.
//
// The scene: ten beads of two sizes, moving and spinning, placed around a
// centre C, under gravity: one pair overlapping, two beads on the floor, one
// against a side wall, the rest free. C = 0 puts the device's float frame
// (Model::origin, the packing's centre rounded to a diameter) on the scene
// origin; C = (50, 20, 30) mm puts it there. Three steps in, the state
// holds x_{n+1}, the half-step velocities v_{n+1/2} and the forces F_n of
// positions x_n; the observables are defined at step n (reduce.cl):
//   v_n = v_{n+1/2} - (F_n/m + g) dt/2,   w_n = w_{n+1/2} - (T_n/I) dt/2,
//   x_n = x_{n+1} - v_{n+1/2} dt,         m = rho 4/3 pi R^3, I = 2/5 m R^2
//   KE = sum m v_n^2 / 2 (and I w_n^2 / 2),  p = sum m v_n,
//   L = sum x_n x m v_n + I w_n,  U_g = -sum m g.x_n,
//   elastic = sum over contacts 2/5 K d^{5/2}, K = 4/3 E* sqrt(R*)
//   contacts = sum over beads of partners touching at x_n (pairs twice).
#include <cmath>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

const Vec3 kOffCentre{0.05, 0.02, 0.03};
constexpr double kFloor = -0.005, kSide = 0.006;  // relative to C
constexpr double kG = 9.81;

Scene observed_scene(Precision p, const Vec3& c) {
  auto at = [&](double x, double y, double z) { return Vec3{c[0] + x, c[1] + y, c[2] + z}; };
  Scene s = empty_scene(p, glass(0.5, 0.3, 5e-5));
  s.effects.gravity = {0, 0, -kG};
  s.walls = {plane("floor", at(0, 0, kFloor), {0, 0, 1}),
             plane("side", at(kSide, 0, 0), {-1, 0, 0})};
  const double a = 1e-3, b = 0.8e-3;
  const double pair = a + b - 1.5e-6;  // beads 1 and 2 along (0.6, 0, 0.8)
  s.particles = {
      sphere(a, at(0, 0, kFloor + a - 2e-6), {0.1, 0, 0}, {0, 5, 0}),
      sphere(a, at(-0.002, -0.002, 0), {0.2, -0.1, 0.05}, {10, 0, -4}),
      sphere(b, at(-0.002 + 0.6 * pair, -0.002, 0.8 * pair), {-0.1, 0.3, 0}, {0, -7, 2}),
      sphere(a, at(kSide - a + 3e-6, 0, 0), {0, 0, 0.1}, {3, 3, 3}),
      sphere(b, at(-0.003, 0.002, kFloor + b - 1e-6), {0, 0.05, -0.02}, {1, 2, 3})};
  for (int k = 0; k < 5; ++k)  // free beads, 2.5 mm apart
    s.particles.push_back(sphere(k % 2 ? b : a, at(-0.006 + 0.0025 * k, 0.003, 0.003),
                                 {0.05 * k - 0.1, 0.02 * k, -0.03}, {k - 2.0, 1, 0.5 * k}));
  return s;
}

double hertz_energy(const Scene& s, double rstar, double d) {
  return 0.4 * 4.0 / 3.0 * e_star(s.materials[0]) * std::sqrt(rstar) * std::pow(d, 2.5);
}

// Elastic energy and contact count of the positions x_n, by geometry.
void contacts_at(const Scene& s, const Vec3& c, const std::vector<Vec3>& x, Observables* o) {
  const size_t n = x.size();
  for (size_t i = 0; i < n; ++i) {
    const double ri = s.particles[i].radius;
    for (size_t j = i + 1; j < n; ++j) {
      const double rj = s.particles[j].radius;
      const double overlap = ri + rj - norm(sub(x[j], x[i]));
      if (overlap <= 0) continue;
      o->contacts += 2;
      o->elastic_energy += hertz_energy(s, ri * rj / (ri + rj), overlap);
    }
    for (double overlap : {ri - (x[i][2] - (c[2] + kFloor)), ri - (c[0] + kSide - x[i][0])})
      if (overlap > 0) {
        o->contacts += 1;
        o->elastic_energy += hertz_energy(s, ri, overlap);
      }
  }
}

Observables host_observables(Simulation& sim, const Vec3& c) {
  const Scene& s = sim.scene();
  const ParticleSnapshot q = download(sim.model(), sim.state());
  const size_t n = q.radius.size();
  const std::vector<double> torque = read_reals(sim.model(), sim.state().torque, 4 * n);
  const double dt = sim.dt(), rho = s.materials[0].density;
  Observables o;
  std::vector<Vec3> xn(n);
  for (size_t i = 0; i < n; ++i) {
    const double r = s.particles[i].radius, m = rho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
    const double inertia = 0.4 * m * r * r;
    Vec3 v, w, p;
    for (int c = 0; c < 3; ++c) {
      const double g = c == 2 ? -kG : 0;
      v[c] = q.velocity[i][c] - 0.5 * dt * (q.force[i][c] / m + g);
      w[c] = q.angular_velocity[i][c] - 0.5 * dt * torque[4 * i + c] / inertia;
      xn[i][c] = q.position[i][c] - dt * q.velocity[i][c];
      p[c] = m * v[c];
      o.momentum[c] += p[c];
    }
    o.kinetic_translational += 0.5 * m * dot(v, v);
    o.kinetic_rotational += 0.5 * inertia * dot(w, w);
    const Vec3 l = cross(xn[i], p);
    for (int c = 0; c < 3; ++c) o.angular_momentum[c] += l[c] + inertia * w[c];
    o.gravitational_energy += m * kG * xn[i][2];
    o.particles += 1;
  }
  contacts_at(s, c, xn, &o);
  return o;
}

// Relative errors achieved: float up to 1.5e-7 (masses, velocities and the
// group sums in float), 8e-6 for the elastic energy (overlaps of ~1e-6 m
// from float positions); double 2e-16, and 2e-12 for the elastic energy
// (the device's pow). A vector's components are compared to its length.
struct Tolerances {
  double energy, elastic, vector;
};
constexpr Tolerances kFloatTol{1e-6, 1e-4, 1e-6}, kDoubleTol{2e-15, 2e-11, 2e-15};

void expect_near_rel(double got, double want, double rel, const char* what) {
  EXPECT_NEAR(got, want, rel * std::fabs(want)) << what;
}
void expect_near_rel(const Vec3& got, const Vec3& want, double rel, const char* what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], rel * norm(want)) << what << " " << c;
}

class Observe : public PrecisionTest {
 protected:
  bool single() const { return GetParam() == Precision::Float; }
  const Tolerances& tol() const { return single() ? kFloatTol : kDoubleTol; }
  void check_moments(Simulation& sim, const Vec3& c) {
    const Observables got = sim.observe();
    const Observables want = host_observables(sim, c);
    expect_near_rel(got.gravitational_energy, want.gravitational_energy, tol().energy,
                    "gravitational energy");
    expect_near_rel(got.angular_momentum, want.angular_momentum, tol().vector, "angular momentum");
  }
};

// Off the scene origin: the sums that do not depend on where x is measured from.
TEST_P(Observe, ReductionsMatchTheHost) {
  Simulation sim(default_device(), observed_scene(GetParam(), kOffCentre));
  sim.advance(3);
  const Observables got = sim.observe();
  const Observables want = host_observables(sim, kOffCentre);
  EXPECT_EQ(got.particles, 10);
  EXPECT_EQ(got.contacts, want.contacts);
  EXPECT_EQ(want.contacts, 2 + 3) << "the scene's one pair (twice) and three wall contacts";
  const Tolerances& t = tol();
  expect_near_rel(got.kinetic_translational, want.kinetic_translational, t.energy, "KE");
  expect_near_rel(got.kinetic_rotational, want.kinetic_rotational, t.energy, "rotational KE");
  expect_near_rel(got.elastic_energy, want.elastic_energy, t.elastic, "elastic energy");
  expect_near_rel(got.momentum, want.momentum, t.vector, "momentum");
}

// Angular momentum and gravitational energy, about the scene origin, for a
// scene whose float frame is the scene's own.
TEST_P(Observe, MomentsAboutTheSceneOrigin) {
  Simulation sim(default_device(), observed_scene(GetParam(), {0, 0, 0}));
  ASSERT_EQ(sim.model().origin(), (Vec3{0, 0, 0}));
  sim.advance(3);
  check_moments(sim, {0, 0, 0});
}

// The same off the scene origin: the device measures x from its float
// frame's origin (Model::origin), and observe() adds origin x P and
// -M g.origin so both are about / relative to the scene origin.
TEST_P(Observe, MomentsAboutTheSceneOriginOffCentre) {
  Simulation sim(default_device(), observed_scene(GetParam(), kOffCentre));
  ASSERT_NE(sim.model().origin(), (Vec3{0, 0, 0}));
  sim.advance(3);
  check_moments(sim, kOffCentre);
}

// Beads 0 and 4 touch only the floor, bead 3 only the side wall: what each
// wall feels is minus the force on its beads.
TEST_P(Observe, WallReactionsAndContactList) {
  Simulation sim(default_device(), observed_scene(GetParam(), kOffCentre));
  sim.advance(3);
  const ParticleSnapshot q = download(sim.model(), sim.state());
  const std::vector<WallReaction> walls = sim.wall_reactions();
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_EQ(walls[0].contacts, 2);
  EXPECT_EQ(walls[1].contacts, 1);
  // achieved: exact (the same numbers summed); float allows a rounding of the sum
  const double rel = single() ? 1e-6 : 1e-15;
  for (int c = 0; c < 3; ++c) {
    const double floor = -(q.force[0][c] + q.force[4][c]), side = -q.force[3][c];
    EXPECT_NEAR(walls[0].force[c], floor, rel * norm(walls[0].force)) << "floor " << c;
    EXPECT_NEAR(walls[1].force[c], side, rel * norm(walls[1].force)) << "side " << c;
  }
  EXPECT_LT(walls[0].force[2], 0) << "the beads push the floor down";
  const std::vector<ContactForce> list = sim.contacts();
  ASSERT_EQ(list.size(), 4u);
  const int want[4][2] = {{1, 2}, {0, -1}, {4, -1}, {3, -2}};
  for (size_t k = 0; k < list.size(); ++k) {
    EXPECT_EQ(list[k].a, want[k][0]);
    EXPECT_EQ(list[k].b, want[k][1]);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(list[k].force[c], q.force[list[k].a][c], rel * norm(q.force[list[k].a]));
  }
}

// A wall moved by a jump has the lists and wall slots rebuilt at the next
// step, not at once: until then the contact list is still the last step's
// (what a settled specimen's packing.txt reads right after its platen is
// lowered), and after it the moved wall's contact is gone.
TEST_P(Observe, ContactListOutlastsAWallJumpUntilTheNextStep) {
  Simulation sim(default_device(), observed_scene(GetParam(), kOffCentre));
  sim.advance(3);
  const std::vector<ContactForce> before = sim.contacts();
  ASSERT_EQ(before.size(), 4u);
  const Vec3 side = sim.wall_point(1);
  sim.set_wall_point(1, {side[0] + 2e-3, side[1], side[2]});  // 2 mm away from bead 3
  const std::vector<ContactForce> after = sim.contacts();
  ASSERT_EQ(after.size(), before.size());
  for (size_t k = 0; k < after.size(); ++k) {
    EXPECT_EQ(after[k].a, before[k].a) << k;
    EXPECT_EQ(after[k].b, before[k].b) << k;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(after[k].force[c], before[k].force[c]) << k << " " << c;
  }
  const std::int64_t builds = sim.state().list_builds;
  sim.advance(1);
  EXPECT_EQ(sim.state().list_builds, builds + 1);
  const std::vector<ContactForce> next = sim.contacts();
  ASSERT_EQ(next.size(), 3u);
  for (const ContactForce& c : next) EXPECT_NE(c.b, -2) << "bead " << c.a << " still on the side wall";
}

// Equal states hash equal; one bit flipped anywhere in the dynamic buffers
// changes the hash, and flipping it back restores it.
TEST_P(Observe, StateHashSeesEveryBit) {
  const Scene s = observed_scene(GetParam(), kOffCentre);
  Simulation a(default_device(), s), b(default_device(), s);
  EXPECT_EQ(a.hash(), b.hash());
  a.advance(3);
  EXPECT_NE(a.hash(), b.hash());
  b.advance(3);
  const std::uint64_t h = a.hash();
  EXPECT_EQ(h, b.hash());
  Device& d = a.model().device();
  for (auto& [name, buf] : a.state().dynamic_buffers()) {
    for (size_t byte : {size_t{0}, buf->bytes / 2, buf->bytes - 1}) {
      unsigned char c = 0;
      d.read(buf->get(), 1, &c, byte);
      c ^= 0x10;
      d.write(buf->get(), 1, &c, byte);
      EXPECT_NE(a.hash(), h) << name << " byte " << byte;
      c ^= 0x10;
      d.write(buf->get(), 1, &c, byte);
      EXPECT_EQ(a.hash(), h) << name << " byte " << byte;
    }
  }
}

SIMSOLS_BOTH_PRECISIONS(Observe);

}  // namespace
}  // namespace simsols::testing
