// Titles made from what a scene sets up (app/experiment/test_title.h), and
// the scale bar's lengths (render/view/frame_caption.h).
#include <gtest/gtest.h>

#include "app/experiment/test_title.h"
#include "solver/io/scene_toml.h"

using namespace simsols;

namespace {
std::string asset(const std::string& name) {
  return std::string(SIMSOLS_SOURCE_DIR) + "/assets/scenes/" + name;
}
}  // namespace

TEST(TestTitle, SaysTheApparatusTheSpecimenAndTheStress) {
  EXPECT_EQ(test_title(load_scene(asset("shear_box.toml"))),
            "Direct shear, 6.35 mm glass beads, σ = 160 kPa");
  EXPECT_EQ(test_title(load_scene(asset("triaxial_sand.toml"))),
            "Triaxial, sand grains (D50 4.76 mm), σ₃ = 100 kPa");
  // a built specimen of clumps (as a checkpoint holds it): the grains' name
  Scene built = load_scene(asset("triaxial_sand.toml"));
  built.apparatus_as<Triaxial>()->specimen.method = Specimen::Method::Given;
  built.apparatus_as<Triaxial>()->specimen.grain = -1;
  built.clumps.push_back(Clump{});
  built.clumps.back().grain = 0;
  EXPECT_EQ(test_title(built), "Triaxial, " + built.grains[0].name + " grains, σ₃ = 100 kPa");
  Scene s = load_scene(asset("shear_box.toml"));
  s.apparatus_as<ShearBox>()->normal_stress = 280e3;
  s.apparatus_as<ShearBox>()->specimen.diameter = 2.38125e-3;
  EXPECT_EQ(test_title(s), "Direct shear, 2.38 mm glass beads, σ = 280 kPa");
  s.apparatus = {};
  s.description = "A bead on a plane";
  EXPECT_EQ(test_title(s), "A bead on a plane");
  s.description.clear();
  EXPECT_EQ(test_title(s), s.name);
}
