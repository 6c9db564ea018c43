// Stability suite, cases of the triaxial cell and the oedometer (ctest
// label `stability`, docs/stability.md): plates that slide past each other
// at the cell's edges, moved by five servos at once, and a plate driven
// into a dense packing at full rate. Reduced forms in CI;
// SIMSOLS_STABILITY_FULL=1 runs the full forms (same assertions).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "solver/apparatus/triaxial/triaxial_programme.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols::testing {
namespace {

const char* form_name() { return stability_full_form() ? "full" : "reduced"; }

// 150 beads of 6.35 mm poured into a 5.5 d square cell, in float.
Scene cell_scene(const std::string& triaxial_extra) {
  return parse_scene(triaxial_cell_toml(glass_toml("0.3"),
                                        "confining_stress = 50e3\nsettle_time = 0.3\nrows = 20\n" +
                                            triaxial_extra,
                                        "float"),
                     "cell.toml");
}

// What a case watches, sampled every `every` steps: NaN, overlaps, the
// fastest bead, and beads whose centre left the cuboid of the plates.
struct Watch {
  Overlaps worst;
  double fastest = 0;
  int escaped = 0;
  bool finite = true;
  double min_side = 1;  // m, the cell's smallest extent seen

  void sample(Simulation& sim, const Triaxial& t) {
    const ParticleSnapshot q = sim.snapshot();
    finite = finite && all_finite(q);
    if (!finite) return;
    const Overlaps o = max_overlaps(sim, q);
    worst.pair = std::max(worst.pair, o.pair);
    worst.wall = std::max(worst.wall, o.wall);
    fastest = std::max(fastest, max_speed(q));
    const int f = t.first_wall;
    const double lo[3] = {sim.wall_point(f + kTriX0)[0], sim.wall_point(f + kTriY0)[1],
                          sim.wall_point(f + kTriFloor)[2]};
    const double hi[3] = {sim.wall_point(f + kTriX1)[0], sim.wall_point(f + kTriY1)[1],
                          sim.wall_point(f + kTriPlaten)[2]};
    for (int k = 0; k < 3; ++k) min_side = std::min(min_side, hi[k] - lo[k]);
    int out = 0;
    for (const Vec3& p : q.position)
      for (int k = 0; k < 3; ++k)
        if (p[k] < lo[k] || p[k] > hi[k]) {
          ++out;
          break;
        }
    escaped = std::max(escaped, out);
  }
};

void run_watched(Simulation& sim, TriaxialProgramme& test, Watch& w, std::int64_t steps,
                 std::int64_t every) {
  const Triaxial& t = *sim.scene().apparatus_as<Triaxial>();
  for (std::int64_t done = 0; done < steps && w.finite && !test.done(); done += every) {
    test.advance(every);
    w.sample(sim, t);
  }
}

// Case 11. Servo plates meeting at the edges: the cell consolidated at
// 50 kPa, then the target jumps to 800 kPa, so the four sides and the
// platen all move in at once, sliding past each other at the cell's
// edges, and back to 50 kPa, so they all move out; then the specimen is
// compressed on the constant-p path (the sides follow the platen). No bead
// may leave the cuboid through a seam, no overlap pass 1 % of d, and each
// jump must end in equilibrium within 1 % of its target. Full form: the
// compression to 20 % instead of 5 %.
TEST(CellEdges, FiveServoPlatesJumpingTogetherLoseNoBead) {
  const bool full = stability_full_form();
  const Scene scene = cell_scene(std::string("path = \"constant_p\"\naxial_strain = ") +
                                 (full ? "0.2" : "0.05") + "\ninertial_number = 1e-3\n");
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(default_device(), scene);
  TriaxialProgramme test(sim);
  test.hold_when_consolidated(true);
  Watch w;
  double worst_error = 0;
  for (double target : {50e3, 800e3, 50e3}) {
    test.set_confining_stress(target);
    while (!test.consolidated_now() && w.finite && sim.time() < 5) run_watched(sim, test, w, 500, 500);
    ASSERT_TRUE(test.consolidated_now()) << "no equilibrium at " << target << " Pa";
    const TriaxialProgramme::AtRest a = test.at_rest();
    for (double s : a.stress) worst_error = std::max(worst_error, std::fabs(s / target - 1));
  }
  const double d = 6.35e-3;
  ASSERT_TRUE(test.start_compression());
  run_watched(sim, test, w, 1LL << 40, 500);
  ASSERT_TRUE(w.finite) << "NaN or inf by step " << sim.steps();
  const TriaxialRow& last = test.rows().back();
  // The constant-p path: p' of the rows against sigma_3, the median and the
  // largest (a collapse drops the platen's stress faster than the sides'
  // servos follow: up to 10 % for one row in the full form).
  std::vector<double> drift;
  for (const TriaxialRow& r : test.rows()) drift.push_back(std::fabs(r.p / 50e3 - 1));
  const double p_drift = *std::max_element(drift.begin(), drift.end());
  std::nth_element(drift.begin(), drift.begin() + drift.size() / 2, drift.end());
  const double p_median = drift[drift.size() / 2];
  std::printf("[measure] cell edges (%s form, float, %zu beads): jumps 50 -> 800 -> 50 kPa, each "
              "plate within %.3f %% of its target at equilibrium; compressed to %.1f %% at "
              "constant p (p' off 50 kPa by %.2f %% in the median row, %.2f %% at most); beads outside the plates' cuboid at most %d "
              "(bound 0); largest overlap bead-bead %.3f %% of d, bead-plate %.3f %% of d "
              "(bound 1 %%); fastest bead %.3g m/s; %lld steps in %.1f s\n",
              form_name(), scene.particles.size(), 100 * worst_error, 100 * last.axial_strain,
              100 * p_median, 100 * p_drift, w.escaped, 100 * w.worst.pair / d, 100 * w.worst.wall / d, w.fastest,
              static_cast<long long>(sim.steps()), seconds_since(t0));
  EXPECT_TRUE(test.done());
  EXPECT_EQ(w.escaped, 0);
  EXPECT_LT(worst_error, 0.01);
  EXPECT_LT(p_median, 0.01);
  EXPECT_LT(w.worst.pair, 0.01 * d);
  EXPECT_LT(w.worst.wall, 0.01 * d);
}

// Case 12. A plate driven into a dense packing at full rate: the cell
// consolidated at 50 kPa, then the platen moved down at the plates' speed
// cap (servo_max_speed, 0.5 m/s: the fastest any apparatus moves a plate;
// 90 x the rate of the default I = 5e-4) while the sides hold sigma_3.
// The beads must neither tunnel through the platen nor escape, the run
// must stay finite, and overlaps stay bounded by the stress the drive
// sets: bound 2 % of d. Full form: to 10 % strain instead of 3 %.
TEST(DrivenPlate, FullRateIntoADensePackingNeitherTunnelsNorExplodes) {
  const bool full = stability_full_form();
  const Scene scene = cell_scene(std::string("axial_strain = ") + (full ? "0.1" : "0.03") + "\n");
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(default_device(), scene);
  TriaxialProgramme test(sim);
  test.hold_when_consolidated(true);
  while (!test.consolidated_now() && sim.time() < 5) test.advance(1 << 14);
  ASSERT_TRUE(test.consolidated_now());
  const TriaxialProgramme::AtRest rest = test.at_rest();
  const double height = rest.volume / (scene.apparatus_as<Triaxial>()->length * scene.apparatus_as<Triaxial>()->width);
  test.set_strain_rate(scene.apparatus_as<Triaxial>()->servo_max_speed / height);
  ASSERT_TRUE(test.start_compression());
  Watch w;
  run_watched(sim, test, w, 1LL << 40, 100);
  ASSERT_TRUE(w.finite) << "NaN or inf by step " << sim.steps();
  const double d = 6.35e-3;
  double peak_q = 0;
  for (const TriaxialRow& r : test.rows()) peak_q = std::max(peak_q, r.q);
  std::printf("[measure] driven plate (%s form, float, %zu beads): platen at %.2f m/s (%.3g 1/s) "
              "to %.1f %%; peak q %.1f kPa; beads outside the plates' cuboid at most %d (bound "
              "0); largest overlap bead-bead %.3f %% of d, bead-plate %.3f %% of d (bound 2 %%); "
              "fastest bead %.3g m/s; %lld steps in %.1f s\n",
              form_name(), scene.particles.size(), scene.apparatus_as<Triaxial>()->servo_max_speed,
              test.strain_rate(), 100 * test.rows().back().axial_strain, peak_q * 1e-3, w.escaped,
              100 * w.worst.pair / d, 100 * w.worst.wall / d, w.fastest,
              static_cast<long long>(sim.steps()), seconds_since(t0));
  EXPECT_TRUE(test.done());
  EXPECT_EQ(w.escaped, 0);
  EXPECT_LT(w.worst.pair, 0.02 * d);
  EXPECT_LT(w.worst.wall, 0.02 * d);
}

}  // namespace
}  // namespace simsols::testing
