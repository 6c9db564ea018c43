// Effect slots (scene.h, Effects; cl_program.h): what a slot set to none
// removes from the kernels, and that removing it changes nothing else.
//   - rolling = "none" against the same scene with mu_r = 0 on every pair in
//     use (the rolling code compiled in through an unused material): the
//     same trajectories, compared number for number (the state hashes may
//     differ: a torque of -0 against none at all);
//   - the per-contact history the State allocates follows the slots: 0, 1
//     or 2 records of 4 reals per list slot and wall slot (the tangential
//     spring and the normal dashpot share the first);
//   - --explain's text names the options.
#include <cmath>
#include <string>

#include "solver/core/slots.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

// A jittered 3 x 3 x 3 lattice of spinning, moving beads falling on a floor:
// many contacts open and close, with relative rolling everywhere.
Scene tumbling_pile(Precision p) {
  Scene s = empty_scene(p, soft(0.5, 0.3, 0.0));
  Material spare = soft(0.5, 0.3, 5e-5);  // used by no particle: only makes mu_r > 0 exist
  spare.name = "spare";
  s.materials.push_back(spare);
  s.effects.gravity = {0, 0, -9.81};
  const double r = 1e-3;
  int k = 0;
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x, ++k) {
        const double j = 0.00002 * r * std::sin(1.7 * k);
        // a stacked cube, slightly overlapping: contacts from the first step
        s.particles.push_back(sphere(r, {x * 1.9998 * r + j, y * 1.9998 * r - j, 0.9999 * r + z * 1.9998 * r},
                                     {0.01 * std::cos(k), 0.01 * std::sin(2.0 * k), 0},
                                     {30 * std::sin(k), 20 * std::cos(3.0 * k), 10.0 * (k % 3)}));
      }
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1})};
  return s;
}

class EffectSlots : public PrecisionTest {};

TEST_P(EffectSlots, RollingNoneEqualsZeroRollingFriction) {
  Scene with = tumbling_pile(GetParam());
  Scene without = with;
  without.effects.rolling = RollingModel::None;
  Simulation a(default_device(), with), b(default_device(), without);
  ASSERT_TRUE(a.model().config().rolling) << "the mu_r = 0 scene must compile the rolling code";
  ASSERT_FALSE(b.model().config().rolling);
  EXPECT_NE(a.model().config().build_options().find("-DHAS_ROLLING"), std::string::npos);
  EXPECT_EQ(b.model().config().build_options().find("-DHAS_ROLLING"), std::string::npos);
  double contacts = 0;
  for (int chunk = 0; chunk < 10; ++chunk) {
    a.advance(500);
    b.advance(500);
    const ParticleSnapshot qa = a.snapshot(), qb = b.snapshot();
    ASSERT_EQ(qa.position.size(), qb.position.size());
    for (size_t i = 0; i < qa.position.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        // == : identical numbers (a zero may differ in sign only)
        ASSERT_EQ(qa.position[i][c], qb.position[i][c]) << "step " << a.steps() << " bead " << i;
        ASSERT_EQ(qa.velocity[i][c], qb.velocity[i][c]) << "step " << a.steps() << " bead " << i;
        ASSERT_EQ(qa.angular_velocity[i][c], qb.angular_velocity[i][c])
            << "step " << a.steps() << " bead " << i;
      }
    contacts = std::max(contacts, a.observe().contacts);
  }
  EXPECT_GT(contacts, 10) << "the pile must be in contact for the comparison to mean anything";
}

TEST_P(EffectSlots, HistoryMemoryFollowsTheSlots) {
  // plane 0, the contact record: the tangential spring and/or the normal
  // dashpot's record; then the elastic rolling torque, then
  // mindlin_deresiewicz's turning point
  struct Case { TangentialModel t; RollingModel r; DampingModel d; int planes; };
  const auto viscous = DampingModel::Viscous, undamped = DampingModel::None;
  const Case cases[] = {{TangentialModel::Mindlin, RollingModel::ConstantTorque, undamped, 1},
                        {TangentialModel::Mindlin, RollingModel::SpringDashpot, viscous, 2},
                        {TangentialModel::None, RollingModel::SpringDashpot, undamped, 1},
                        {TangentialModel::None, RollingModel::ConstantTorque, viscous, 1},
                        {TangentialModel::None, RollingModel::None, undamped, 0},
                        {TangentialModel::MindlinDeresiewicz, RollingModel::ConstantTorque, viscous, 2},
                        {TangentialModel::MindlinDeresiewicz, RollingModel::SpringDashpot, undamped, 3}};
  const size_t real = GetParam() == Precision::Double ? 8 : 4;
  for (const Case& c : cases) {
    Scene s = tumbling_pile(GetParam());
    s.effects.tangential = c.t;
    s.effects.rolling = c.r;
    s.effects.damping = c.d;
    // the layout as the kernels will be built for it
    const KernelConfig k = make_kernel_config(s, *default_device());
    SCOPED_TRACE(compiled_slots_line(s, k));
    EXPECT_EQ(k.history_planes(), c.planes);
    EXPECT_EQ(k.history_bytes_per_contact(), c.planes * 4 * real);
    EXPECT_NE(k.build_options().find("-DHIST_PLANES=" + std::to_string(c.planes)), std::string::npos);
    // each compiled sub-model's plane, numbered in the table's order
    const bool record = k.friction || k.damping, roll = c.r == RollingModel::SpringDashpot;
    const std::string o = k.build_options() + " ";
    EXPECT_EQ(o.find(" -DHIST_CONTACT=0 ") != std::string::npos, record) << o;
    EXPECT_EQ(o.find(record ? " -DHIST_ROLL=1 " : " -DHIST_ROLL=0 ") != std::string::npos, roll) << o;
    EXPECT_EQ(o.find("-DHIST_ROLL=") != std::string::npos, roll) << o;
    const bool turn = c.t == TangentialModel::MindlinDeresiewicz;
    EXPECT_EQ(o.find(" -DHIST_TURN=" + std::to_string(c.planes - 1) + " ") != std::string::npos, turn)
        << o;
    EXPECT_EQ(k.shared_rolling_cap(), c.r == RollingModel::ConstantTorque);
    const std::string text = explain_effects(s, k);
    EXPECT_NE(text.find(std::to_string(c.planes * 4 * real) + " bytes per contact"),
              std::string::npos) << text;
    // Built and run (each a kernel build of its own): the empty layout, the
    // widest (three planes) and, in float, the rolling spring alone on plane
    // 0; the byte counts scale with the real's size.
    const bool run = c.planes == 0 || c.planes == 3 || (real == 4 && roll && !record);
    if (!run) continue;
    Simulation sim(default_device(), s);
    EXPECT_EQ(sim.model().config(), k) << "the simulation compiles the layout asked";
    const State& st = sim.state();
    sim.advance(300);
    EXPECT_GT(st.up_slots, 0);
    const size_t list = size_t(st.up_slots) * c.planes * 4 * real;
    EXPECT_EQ(st.spring.bytes, std::max<size_t>(16, list));  // 16: the stand-in when none
    EXPECT_EQ(st.wall_spring.bytes,
              std::max<size_t>(16, size_t(st.wall_slots) * c.planes * 4 * real));
    EXPECT_TRUE(std::isfinite(sim.observe().kinetic()));
  }
}

SIMSOLS_BOTH_PRECISIONS(EffectSlots);

}  // namespace
}  // namespace simsols::testing
