// Helpers shared by the tests: scenes built in code, and the precisions
// every physics test runs in.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "solver/scene/scene.h"
#include "solver/apparatus/shear_box/shear_box.h"
#include "solver/core/simulation.h"

namespace simsols {

// The tests' OpenCL device, opened once with the options the environment
// asks for (engine_options_from_environment: the gpu_form label sets
// SIMSOLS_LANES=1).
std::shared_ptr<Device> default_device();

}  // namespace simsols

namespace simsols::testing {

// Sets one environment variable (nullptr: unsets it) for its scope and
// restores the old value, or its absence, after.
class ScopedVariable {
 public:
  ScopedVariable(const char* name, const char* value);
  ~ScopedVariable();
  ScopedVariable(const ScopedVariable&) = delete;
  ScopedVariable& operator=(const ScopedVariable&) = delete;

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

// Glass of the reference paper (its Table 2), with chosen e and friction.
Material glass(double restitution = 0.87, double mu_s = 0.0, double mu_r = 0.0);
// A soft polymer (E = 0.5 GPa): larger stable steps for long-duration tests.
Material soft(double restitution, double mu_s, double mu_r);

Scene empty_scene(Precision p, const Material& m);
Particle sphere(double radius, Vec3 position, Vec3 velocity = {}, Vec3 omega = {});
Wall plane(const std::string& name, Vec3 point, Vec3 normal);

// A cap free to tilt (Wall::tilts) over two spheres of radii r_left and
// r_right, 20 mm apart on a floor, soft polymer, gravity: a 30 x 10 mm plate
// (wall 1) just above the taller, loaded with 1 N as a dead weight of
// 0.01 kg or, without one, by a PI servo (then held level).
Scene tilting_cap_scene(Precision p, double r_left, double r_right, bool dead_weight);

double mass(const Scene& s, const Particle& p);

// The suite's reduced direct shear specimen: the paper's 6.35 mm glass
// beads, 5 x 5 per layer in a box with the paper's relative clearance,
// 4 layers (seed 5), 100 rows, float. Built (build_shear_box), not yet
// validated: callers may change effects or rows and then validate_scene.
Scene small_shear_box(const std::string& name, double sigma, double displacement,
                      Precision p = Precision::Float,
                      Specimen::Method method = Specimen::Method::Layers);

// No NaN or infinity in positions, velocities or spins.
bool all_finite(const ParticleSnapshot& q);

// The stability suite's full forms (SIMSOLS_STABILITY_FULL=1, docs/stability.md).
bool stability_full_form();

// The stability suite's measurements (docs/stability.md). The fastest
// bead's speed (m/s).
double max_speed(const ParticleSnapshot& q);
// Largest overlaps of the current state, in metres: between two beads
// (all pairs: the specimens here hold a few hundred beads) and between a
// bead and a wall (at the walls' current positions; planes one-sided,
// rectangles two-sided plates, as in the solver and check_wall_overlaps).
struct Overlaps {
  double pair = 0, wall = 0;
  double largest() const { return std::max(pair, wall); }
};
Overlaps max_overlaps(Simulation& sim, const ParticleSnapshot& q);
double seconds_since(std::chrono::steady_clock::time_point t0);

// Equivalent Young modulus of a material with itself, and with a rigid-free
// same-material wall (identical).
double e_star(const Material& m);

// The paper's glass (Table 2) as a scene file's [[materials]] table named
// "glass", with the given sliding friction.
std::string glass_toml(const std::string& sliding_friction = "0.02");

// The triaxial tests' cell: 150 beads of 6.35 mm poured into a 5.5 d
// (34.925 mm) square cell, after `materials` (a "glass" material), with
// `triaxial_keys` in [triaxial], in `precision`.
std::string triaxial_cell_toml(const std::string& materials, const std::string& triaxial_keys,
                               const std::string& precision);

// Parses `text` as the file "bad.toml" and expects it refused with a
// SceneError of this code at this field, its message naming the file.
void expect_scene_error(const std::string& text, const std::string& code,
                        const std::string& field);

// Prints "[measure] what: measured M, theory T, error E%" so the test log
// doubles as the validation record (docs/validation.md).
void report(const std::string& what, double measured, double theory);

inline const char* precision_name(Precision p) {
  return p == Precision::Float ? "float" : "double";
}

// Parameterised fixture base: every physics test runs in float and double.
class PrecisionTest : public ::testing::TestWithParam<Precision> {};

#define SIMSOLS_BOTH_PRECISIONS(Suite)                                                \
  INSTANTIATE_TEST_SUITE_P(, Suite,                                                   \
                           ::testing::Values(::simsols::Precision::Float,             \
                                             ::simsols::Precision::Double),           \
                           [](const auto& info) {                                     \
                             return std::string(::simsols::testing::precision_name(   \
                                 info.param));                                        \
                           })

}  // namespace simsols::testing
