// The enumerated choices (solver/scene/choices.h): every value has one
// name that reads back to it, and the scene loader's message for a bad
// choice lists exactly the table's names.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "solver/common/errors.h"
#include "solver/io/scene_toml.h"
#include "solver/scene/choices.h"

namespace simsols {
namespace {

template <class E>
void expect_round_trip(size_t count) {
  const auto table = choices<E>();
  EXPECT_EQ(table.size(), count);
  std::set<std::string> names;
  for (const Named<E>& c : table) {
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate name " << c.name;
    EXPECT_STREQ(choice_name(c.value), c.name);
    ASSERT_TRUE(parse_choice<E>(c.name).has_value()) << c.name;
    EXPECT_EQ(*parse_choice<E>(c.name), c.value) << c.name;
  }
  EXPECT_FALSE(parse_choice<E>("no_such_choice").has_value());
  EXPECT_EQ(choice_names<E>().size(), count);
}

TEST(Choices, EveryValueHasOneNameThatReadsBack) {
  expect_round_trip<DampingModel>(2);
  expect_round_trip<TangentialModel>(3);
  expect_round_trip<RollingModel>(3);
  expect_round_trip<CohesionModel>(2);
  expect_round_trip<FluidModel>(2);
  expect_round_trip<Precision>(2);
  expect_round_trip<WallShape>(2);
  expect_round_trip<ShearBox::Loading>(2);
  expect_round_trip<Specimen::Method>(3);
  expect_round_trip<Specimen::Clearance>(2);
}

TEST(Choices, TheLoaderListsTheTablesNames) {
  const char* scene = R"(
[[materials]]
name = "glass"
young_modulus = 6.3e10
poisson_ratio = 0.23
density = 2500
restitution = 0.87

[[particles]]
material = "glass"
radius = 1e-3
position = [0, 0, 0]

[effects]
rolling = "spring"

[numerics]
duration = 1e-3
)";
  try {
    parse_scene(scene, "choices.toml");
    FAIL() << "rolling = \"spring\" accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "bad_enum");
    EXPECT_EQ(e.field, "effects.rolling");
    const std::string what = e.what();
    for (const std::string& name : choice_names<RollingModel>())
      EXPECT_NE(what.find("\"" + name + "\""), std::string::npos) << name << " in " << what;
  }
}

}  // namespace
}  // namespace simsols
