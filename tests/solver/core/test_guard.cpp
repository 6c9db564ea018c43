// The runaway guard (solver/core/guard.h) on scenes whose runaway step is
// known by hand.
//
// Free fall under the leapfrog (integrate.cl) from a half-step velocity v0:
//   v_k = v0 - k g dt,   z_k = z_0 + dt sum_{j=1..k} v_j = z_0 + k v0 dt - g dt^2 k (k+1) / 2
// and a bead is marked when |v_k| dt > R / 10. With R = 1 mm, dt = 1 ms and
// g = 9.81 m/s^2 a bead falling from rest moves 0.981 R/10 in step 10 and
// 1.079 R/10 in step 11: step 11 is the first bad step (margins 2 % and 8 %,
// far above float rounding). Bead 0, thrown up at 0.05 m/s, crosses only at
// step 16, so step 11 marks beads 1 and 2 and names bead 1, the lowest index.
#include <cmath>
#include <optional>

#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

constexpr double kR = 1e-3, kDt = 1e-3, kG = 9.81;
constexpr std::int64_t kFirstBad = 11;
constexpr double kThrown = 0.05;  // bead 0's upward start, m/s

double fall_z(double v0, std::int64_t k) {
  return double(k) * v0 * kDt - kG * kDt * kDt * double(k * (k + 1)) / 2;
}
double fall_v(double v0, std::int64_t k) { return v0 - kG * kDt * double(k); }

// Friction, rolling resistance, damping, gravity and a (distant) floor in
// every scene here: one kernel build per precision, the one
// test_determinism and test_stability use too.
Scene guard_scene(Precision p) {
  Scene s = empty_scene(p, glass(0.5, 0.3, 5e-5));
  s.effects.gravity = {0, 0, -kG};
  s.walls = {plane("floor", {0, 0, -1}, {0, 0, 1})};
  return s;
}

// Three free beads, dt forced to 1 ms (no contact: stability is not at stake).
// A skin of 5 cm puts the list checks ~60 steps apart, so the guard must find
// the mark through its copies and readings, not a list check.
Scene falling_beads(Precision p, double skin = 0) {
  Scene s = guard_scene(p);
  s.particles = {sphere(kR, {0, 0, 0}, {0, 0, kThrown}), sphere(kR, {0.01, 0, 0}),
                 sphere(kR, {0.02, 0, 0})};
  s.numerics.dt = kDt;
  s.numerics.force_dt = true;
  s.numerics.skin = skin;
  return s;
}

// Host writes a replay must repeat: bead 2 moved sideways at step 5 (before
// any copy but the first), bead 1 at step 10 (the step before the fault).
constexpr double kNudge2 = 1e-3, kNudge1 = 2e-3;
void drive(Simulation& sim) {
  if (sim.steps() == 5) sim.nudge_particle(2, {0, kNudge2, 0});
  if (sim.steps() == 10) sim.nudge_particle(1, {0, kNudge1, 0});
}

std::optional<Fault> run_to_fault(Simulation& sim, std::int64_t max_steps) {
  try {
    while (sim.steps() < max_steps) {
      drive(sim);
      sim.advance(1);
    }
    sim.check();
  } catch (const RunawayError& e) {
    return e.fault();
  }
  return std::nullopt;
}

class GuardFault : public PrecisionTest {
 protected:
  bool single() const { return GetParam() == Precision::Float; }
  // Errors achieved against the formulas: double none (at most 1e-19 m); float
  // 7e-11 m and 7e-9 m/s (g and dt round to float, 4e-8 relative), 2e-18 m
  // on a nudged coordinate (compensated sums).
  double z_tol() const { return single() ? 1e-9 : 1e-18; }
  double v_tol() const { return single() ? 1e-7 : 1e-16; }
  double nudge_tol() const { return single() ? 2e-17 : 1e-18; }
};

TEST_P(GuardFault, NamesTheFirstBadStepAndItsLowestParticle) {
  for (std::int64_t interval : {simsols::Guard::kDefaultInterval, std::int64_t{4}}) {
    SCOPED_TRACE("guard interval " + std::to_string(interval));
    Simulation sim(default_device(), falling_beads(GetParam()));
    sim.guard().set_interval(interval);
    const std::optional<Fault> f = run_to_fault(sim, 100);
    ASSERT_TRUE(f) << "the beads never ran away";
    EXPECT_TRUE(f->located);
    EXPECT_FALSE(f->non_finite);
    EXPECT_EQ(f->step, kFirstBad);
    EXPECT_EQ(f->particle, 1);
    EXPECT_EQ(f->marked, 2) << "beads 1 and 2, not the thrown bead 0";
    EXPECT_NEAR(f->time, kFirstBad * kDt, 1e-17);
    EXPECT_NEAR(f->limit, 0.1 * kR, single() ? 5e-11 : 1e-19);  // of the device's radius
    EXPECT_NEAR(f->velocity[2], fall_v(0, kFirstBad), v_tol());
    EXPECT_NEAR(f->moved, -fall_v(0, kFirstBad) * kDt, v_tol() * kDt);
    EXPECT_NEAR(f->position[0], 0.01, 1e-17);
    EXPECT_NEAR(f->position[1], kNudge1, nudge_tol());
    EXPECT_NEAR(f->position[2], fall_z(0, kFirstBad), z_tol());
    const std::string what = RunawayError(*f).what();
    EXPECT_NE(what.find("step 11 "), std::string::npos) << what;
    EXPECT_NE(what.find("particle 1,"), std::string::npos) << what;
    EXPECT_NE(what.find("moved more than a tenth of its radius"), std::string::npos) << what;
  }
}

// Left at the step before, with the host's writes of that step replayed,
// bit for bit what an unguarded run of the pipeline reaches; the run can be
// retried from there and meets the same fault.
TEST_P(GuardFault, LeavesTheStateOfTheStepBefore) {
  for (std::int64_t interval : {simsols::Guard::kDefaultInterval, std::int64_t{4}}) {
    SCOPED_TRACE("guard interval " + std::to_string(interval));
    Simulation sim(default_device(), falling_beads(GetParam()));
    sim.guard().set_interval(interval);
    ASSERT_TRUE(run_to_fault(sim, 100));
    ASSERT_EQ(sim.steps(), kFirstBad - 1);
    const ParticleSnapshot q = sim.snapshot();  // the guard is clear again: no throw
    EXPECT_NEAR(q.position[0][2], fall_z(kThrown, kFirstBad - 1), z_tol());
    EXPECT_NEAR(q.position[1][2], fall_z(0, kFirstBad - 1), z_tol());
    EXPECT_NEAR(q.position[2][1], kNudge2, nudge_tol()) << "the write of step 5 replayed";
    EXPECT_NEAR(q.position[1][1], kNudge1, nudge_tol()) << "the write of step 10 replayed";
    EXPECT_NEAR(q.velocity[1][2], fall_v(0, kFirstBad - 1), v_tol());

    Simulation twin(default_device(), falling_beads(GetParam()));
    while (twin.steps() < kFirstBad - 1) {
      drive(twin);
      step(twin.model(), twin.state());  // the pipeline alone, no guard
    }
    drive(twin);
    EXPECT_EQ(sim.hash(), twin.hash()) << "bit for bit the unguarded state";

    const std::optional<Fault> again = run_to_fault(sim, 100);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->step, kFirstBad);
    EXPECT_EQ(again->particle, 1);
    EXPECT_EQ(sim.steps(), kFirstBad - 1);
  }
}

// No reading returns a state past the bad step, even when no list check
// falls between the bad step and the reading.
TEST_P(GuardFault, NoReadingHoldsTheBadStep) {
  Simulation sim(default_device(), falling_beads(GetParam(), 0.05));
  std::int64_t last_read = -1;
  bool threw = false;
  try {
    while (sim.steps() < 60) {
      sim.advance(1);
      const ParticleSnapshot q = sim.snapshot();
      last_read = sim.steps();
      ASSERT_LE(norm(q.velocity[1]) * kDt, 0.1 * kR) << "a reading held a runaway";
    }
  } catch (const RunawayError& e) {
    threw = true;
    EXPECT_EQ(e.fault().step, kFirstBad);
  }
  EXPECT_TRUE(threw);
  EXPECT_EQ(last_read, kFirstBad - 1);
}

// A host write of a NaN is caught by the next step: both beads named as
// not finite, the lowest index first.
TEST_P(GuardFault, NaNWrittenByTheHostIsNamed) {
  Simulation sim(default_device(), falling_beads(GetParam()));
  std::optional<Fault> f;
  try {
    sim.advance(3);
    sim.nudge_particle(2, {std::nan(""), 0, 0});
    sim.nudge_particle(1, {0, std::nan(""), 0});
    sim.advance(5);
    sim.check();
  } catch (const RunawayError& e) {
    f = e.fault();
    EXPECT_NE(std::string(e.what()).find("NaN or infinite"), std::string::npos) << e.what();
  }
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->located);
  EXPECT_TRUE(f->non_finite);
  EXPECT_EQ(f->step, 4);
  EXPECT_EQ(f->particle, 1);
  EXPECT_EQ(f->marked, 2);
  EXPECT_EQ(sim.steps(), 3);
}

SIMSOLS_BOTH_PRECISIONS(GuardFault);

// A settling pile (contacts, friction, list rebuilds) with a copy every 3
// steps and readings: never interrupted, and the guard changes nothing: the
// state is bit for bit that of the pipeline run alone.
TEST(GuardQuiet, SettlingPileIsNeverInterrupted) {
  Scene s = guard_scene(Precision::Float);
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  const double spacing = 1.9998 * kR;  // touching: forces from the first step
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 4; ++k)
        s.particles.push_back(
            sphere(kR, {spacing * i, spacing * j, kR + spacing * k}, {0, 0, -0.2}));
  s.numerics.skin = 2e-6;  // a tiny skin: list rebuilds the copies must hold
  Simulation sim(default_device(), s), twin(default_device(), s);
  sim.guard().set_interval(3);
  double contacts = 0;
  EXPECT_NO_THROW({
    for (int k = 0; k < 40; ++k) {
      sim.advance(10);
      contacts = std::max(contacts, sim.observe().contacts);
      sim.snapshot();
    }
  });
  EXPECT_GT(contacts, 50) << "the pile must come into contact";
  EXPECT_GT(sim.state().list_builds, 1);
  for (int k = 0; k < 400; ++k) step(twin.model(), twin.state());
  EXPECT_EQ(sim.steps(), 400);
  EXPECT_EQ(sim.hash(), twin.hash());
}

// The header's figure: a 10 m/s impact of a 2.38 mm glass bead at the
// default step moves it by well under the guard's tenth of a radius per
// step (the header says 0.3 %), and passes without a fault.
TEST(GuardQuiet, TenMetrePerSecondImpactPasses) {
  Scene s = guard_scene(Precision::Float);
  const double r = 2.38e-3 / 2;
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  s.particles = {sphere(r, {0, 0, r + 1e-5}, {0, 0, -10})};
  Simulation sim(default_device(), s);
  double worst = 0;
  bool ended = false;
  EXPECT_NO_THROW({
    for (int k = 0; k < 2000 && !ended; ++k) {
      sim.advance(1);
      const ParticleSnapshot q = sim.snapshot();
      worst = std::max(worst, norm(q.velocity[0]) * sim.dt() / r);
      ended = q.velocity[0][2] > 0 && q.contacts[0] == 0;
    }
  });
  EXPECT_TRUE(ended) << "the bead did not rebound";
  EXPECT_LT(worst, 0.003);
}

TEST(GuardSettings, IntervalAndBackupSize) {
  Scene s = guard_scene(Precision::Double);
  s.particles = {sphere(kR, {0, 0, kR}), sphere(kR, {0.01, 0, kR})};
  Simulation sim(default_device(), s);
  simsols::Guard& g = sim.guard();
  EXPECT_EQ(g.interval(), simsols::Guard::kDefaultInterval);
  g.set_interval(7);
  EXPECT_EQ(g.interval(), 7);
  EXPECT_THROW(g.set_interval(0), std::invalid_argument);
  EXPECT_THROW(g.set_interval(-5), std::invalid_argument);
  EXPECT_EQ(g.interval(), 7);
  size_t dynamic = 0;
  for (auto& [name, buffer] : sim.state().dynamic_buffers()) dynamic += buffer->bytes;
  EXPECT_EQ(g.backup_bytes(), dynamic) << "one copy of the dynamic buffers";
}

}  // namespace
}  // namespace simsols::testing
