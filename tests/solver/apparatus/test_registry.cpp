// The registry of apparatus (registry.h): one entry per alternative of
// Scene::apparatus, found by scene and by name, each with a table reader
// (solver/io/scene_tables_apparatus.cpp); one apparatus per scene whatever
// the tables' order; the built-in scenes of each kind read back as that
// kind, their test made by the registry.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "solver/apparatus/registry.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "solver/common/errors.h"
#include "solver/io/scene_tables.h"
#include "solver/io/scene_toml.h"
#include "tests/support/test_support.h"

namespace simsols {
namespace {

std::string scene_file(const std::string& name) {
  return std::string(SIMSOLS_SOURCE_DIR) + "/assets/scenes/" + name;
}

TEST(ApparatusRegistry, OneEntryPerAlternativeWithUniqueNames) {
  const auto kinds = apparatus_kinds();
  ASSERT_EQ(kinds.size() + 1, std::variant_size_v<Apparatus>);
  std::set<std::string> names, labels;
  for (const ApparatusKind& k : kinds) {
    names.insert(k.name);
    labels.insert(k.label);
    EXPECT_EQ(find_apparatus_kind(k.name), &k);
    EXPECT_TRUE(scene_toml::has_apparatus_reader(k.name)) << k.name;
    // every kind but the periodic cell (no walls: its space repeats) adds walls
    if (std::string(k.name) != "periodic_cell") EXPECT_GT(k.walls, 0) << k.name;
    else EXPECT_EQ(k.walls, 0);
    EXPECT_NE(k.build, nullptr);
    EXPECT_NE(k.make_programme, nullptr);
  }
  EXPECT_EQ(names.size(), kinds.size());
  EXPECT_EQ(labels.size(), kinds.size());
  EXPECT_EQ(find_apparatus_kind("shear box"), nullptr);
  EXPECT_EQ(apparatus_names("|"), "shear_box|oedometer|triaxial|periodic_cell");
}

TEST(ApparatusRegistry, EachBuiltInSceneIsItsKind) {
  for (const char* kind : {"shear_box", "oedometer", "triaxial"}) {
    const Scene s = load_scene(scene_file(std::string(kind) + ".toml"));
    ASSERT_NE(apparatus_kind(s), nullptr) << kind;
    EXPECT_STREQ(apparatus_kind(s)->name, kind);
    ASSERT_NE(s.cell(), nullptr);
    EXPECT_EQ(s.specimen(), &s.cell()->specimen);
    // its walls are the last ones added, as many as the registry says
    EXPECT_EQ(s.cell()->first_wall + apparatus_kind(s)->walls, int(s.walls.size())) << kind;
  }
  // the periodic cell: no cell of walls, no specimen table; its space repeats
  const Scene cell = load_scene(scene_file("periodic_cell.toml"));
  ASSERT_NE(apparatus_kind(cell), nullptr);
  EXPECT_STREQ(apparatus_kind(cell)->name, "periodic_cell");
  EXPECT_EQ(cell.cell(), nullptr);
  EXPECT_TRUE(cell.walls.empty());
  EXPECT_TRUE(cell.periodic.has_value());
  Scene none = load_scene(scene_file("example_minimal.toml"));
  EXPECT_EQ(apparatus_kind(none), nullptr);
  EXPECT_EQ(none.cell(), nullptr);
  EXPECT_EQ(none.specimen(), nullptr);
  try {
    required_apparatus_kind(none);
    FAIL() << "a scene without an apparatus has no kind";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "no_apparatus");
    EXPECT_NE(std::string(e.what()).find("shear_box, oedometer, triaxial, periodic_cell"), std::string::npos)
        << e.what();
  }
}

TEST(ApparatusRegistry, MakesTheTestOfTheScenesKind) {
  const Scene s = load_scene(scene_file("shear_box.toml"));
  Simulation sim(default_device(), s);
  const std::unique_ptr<ApparatusProgramme> test = make_programme(sim);
  ASSERT_NE(dynamic_cast<ShearProgramme*>(test.get()), nullptr);
  EXPECT_STREQ(test->rows_file(), "shear.csv");
  EXPECT_EQ(test->row_count(), 0u);
  EXPECT_STREQ(test->stage_name(), "settle");
}

// A prepared specimen's top against the apparatus: the shear box refuses a
// shear plane at or above it and names the field; kinds without such a
// check have none.
TEST(ApparatusRegistry, TheShearBoxChecksItsPlaneAgainstThePreparedTop) {
  const Scene s = load_scene(scene_file("shear_box.toml"));
  const ApparatusKind& kind = required_apparatus_kind(s);
  ASSERT_NE(kind.check_specimen_top, nullptr);
  const double plane = s.apparatus_as<ShearBox>()->split_height;
  ASSERT_GT(plane, 0);
  EXPECT_FALSE(kind.check_specimen_top(s, 1.01 * plane));
  const std::optional<SceneIssue> issue = kind.check_specimen_top(s, 0.99 * plane);
  ASSERT_TRUE(issue);
  EXPECT_EQ(issue->code, "out_of_range");
  EXPECT_EQ(issue->field, "shear_box.split_height");
  EXPECT_EQ(find_apparatus_kind("oedometer")->check_specimen_top, nullptr);
}

// Two apparatus tables: refused at the second in the registry's order,
// whichever comes first in the file.
TEST(ApparatusRegistry, OneApparatusPerSceneWhateverTheOrder) {
  const std::string shear = "[shear_box]\n[shear_box.specimen]\nmethod = \"layers\"\n"
                            "material = \"glass\"\ndiameter = 6.35e-3\nlayers = 1\n";
  const std::string triaxial = "[triaxial]\n[triaxial.specimen]\nmethod = \"layers\"\n"
                               "material = \"glass\"\ndiameter = 6.35e-3\nlayers = 1\n";
  const std::string glass = testing::glass_toml();
  testing::expect_scene_error(glass + shear + triaxial, "conflicting_keys", "triaxial");
  testing::expect_scene_error(glass + triaxial + shear, "conflicting_keys", "triaxial");
}

}  // namespace
}  // namespace simsols
