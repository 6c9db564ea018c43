// Run profiles (solver/apparatus/run_profile.h): `paper` leaves a scene as it is,
// `fast` softens the grains no further than its stiffness-number floor,
// lengthens the step and raises the shear box's inertial number, and both a
// bad name and an apparatus it was not measured on are refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "solver/common/errors.h"
#include "solver/io/scene_toml.h"
#include "solver/apparatus/run_profile.h"

namespace simsols {
namespace {

Scene read_asset(const char* name) {
  return read_scene(std::string(SIMSOLS_SOURCE_DIR "/assets/scenes/") + name);
}

TEST(RunProfile, PaperChangesNothing) {
  const Scene given = read_asset("shear_box.toml");
  Scene s = given;
  const ProfileApplied a = apply_profile(s, run_profile("paper"), "shear_box.toml");
  for (size_t m = 0; m < s.materials.size(); ++m)
    EXPECT_EQ(s.materials[m].young_modulus, given.materials[m].young_modulus);
  EXPECT_EQ(s.numerics.dt_fraction, given.numerics.dt_fraction);
  EXPECT_EQ(s.apparatus_as<ShearBox>()->inertial_number,
            given.apparatus_as<ShearBox>()->inertial_number);
  EXPECT_EQ(a.stiffness_scale, 1.0);
  EXPECT_GT(a.kappa, 1000);  // the paper's glass at 160 kPa: about 2 600
}

TEST(RunProfile, FastLengthensTheStepAndSpeedsTheShear) {
  const Scene given = read_asset("shear_box.toml");
  Scene s = given;
  const ProfileApplied a = apply_profile(s, run_profile("fast"), "shear_box.toml");
  EXPECT_EQ(a.stiffness_scale, 1.0);  // measured: E x 0.1 moved the 3.97 mm peaks (accuracy.md)
  for (size_t m = 0; m < s.materials.size(); ++m)
    EXPECT_EQ(s.materials[m].young_modulus, given.materials[m].young_modulus);
  EXPECT_EQ(s.numerics.dt_fraction, 0.5);
  EXPECT_EQ(s.apparatus_as<ShearBox>()->inertial_number, 2e-3);
}

// A stiffness lever (E x 0.1) keeps kappa = (E*/sigma)^(2/3) above its
// floor: at 160 kPa it applies in full, at 2 MPa (kappa 644 at full
// stiffness) only as far as kappa = 400.
TEST(RunProfile, AStiffnessLeverKeepsKappaAboveItsFloor) {
  const RunProfile soft{"soft", "E x 0.1, kappa >= 400", 0.1, 400, 0, 0};
  Scene s = read_asset("shear_box.toml");
  Scene same = s;
  const double paper_kappa = apply_profile(same, run_profile("paper"), "x").kappa;
  const ProfileApplied a = apply_profile(s, soft, "shear_box.toml");
  EXPECT_DOUBLE_EQ(a.stiffness_scale, 0.1);
  EXPECT_NEAR(a.kappa, std::pow(0.1, 2.0 / 3.0) * paper_kappa, 1e-9 * a.kappa);
  Scene high = read_asset("shear_box.toml");
  high.apparatus_as<ShearBox>()->normal_stress = 2e6;  // kappa 644: x 0.1^(2/3) would be 139
  const ProfileApplied b = apply_profile(high, soft, "shear_box.toml");
  EXPECT_NEAR(b.stiffness_scale, std::pow(400 / 644.0, 1.5), 0.01);
  EXPECT_NEAR(b.kappa, 400, 1e-9 * 400);
}

TEST(RunProfile, AGivenShearSpeedIsKept) {
  Scene s = read_asset("shear_box.toml");
  s.apparatus_as<ShearBox>()->shear_speed = 1e-3;
  const double before = s.apparatus_as<ShearBox>()->inertial_number;
  apply_profile(s, run_profile("fast"), "shear_box.toml");
  EXPECT_EQ(s.apparatus_as<ShearBox>()->inertial_number, before);
}

TEST(RunProfile, BadNamesAndOtherApparatusAreRefusedByName) {
  try {
    run_profile("quick");
    FAIL() << "no such profile";
  } catch (const UsageError& e) {
    EXPECT_EQ(e.field, "--profile");
    EXPECT_NE(e.message.find("paper, fast"), std::string::npos) << e.message;
  }
  Scene tri = read_asset("triaxial.toml");
  try {
    apply_profile(tri, run_profile("fast"), "triaxial.toml");
    FAIL() << "the fast profile is measured on the shear box only";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "not_applicable");
    EXPECT_EQ(e.file, "triaxial.toml");
  }
  EXPECT_NO_THROW(apply_profile(tri, run_profile("paper"), "triaxial.toml"));
}

}  // namespace
}  // namespace simsols
