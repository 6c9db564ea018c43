// The paper's programme (app/experiment/shear_box/paper_tests.h): sizes as the docs and the lab's
// panel print them (rounded to 0.01 mm) name the exact Table 1 sizes, which
// are 3/32, 1/8, 5/32, 3/16 and 1/4 inch; other sizes are refused with the
// list of the accepted ones, naming the base scene but no other file.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/common/errors.h"
#include "app/experiment/shear_box/paper_tests.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

TEST(PaperTests, PrintedSizesNameTheTable1Sizes) {
  const std::pair<double, double> printed[] = {
      {2.38, 2.38125}, {3.18, 3.175}, {3.97, 3.96875}, {4.76, 4.7625}, {6.35, 6.35}};
  for (auto [text, exact] : printed) {
    ASSERT_TRUE(nearest_table1_size(text).has_value()) << text;
    EXPECT_EQ(*nearest_table1_size(text), exact) << text;
    EXPECT_EQ(*nearest_table1_size(exact), exact) << exact;
  }
  for (double inch_32nds : {3.0, 4.0, 5.0, 6.0, 8.0})
    EXPECT_TRUE(nearest_table1_size(inch_32nds * 25.4 / 32).has_value()) << inch_32nds;
  EXPECT_EQ(table1_layers(4.76), 4);
  EXPECT_EQ(table1_layers(2.38), 8);
  EXPECT_EQ(table1_layers(3.18), 6);
  EXPECT_EQ(table1_layers(3.97), 5);
}

TEST(PaperTests, SizesFartherThanHalfAPercentAreNotTable1Sizes) {
  // 0.5 % of 4.7625 is 0.0238 mm
  EXPECT_TRUE(nearest_table1_size(4.7625 * 1.0049).has_value());
  EXPECT_FALSE(nearest_table1_size(4.7625 * 1.0051).has_value());
  EXPECT_FALSE(nearest_table1_size(4.7625 * 0.9949).has_value());
  for (double d : {0.0, -4.76, 1.0, 5.0, 7.0, 4.8})
    EXPECT_FALSE(nearest_table1_size(d).has_value()) << d;
  EXPECT_EQ(table1_layers(5.0), 0);
  EXPECT_EQ(table1_sizes_text(), "2.38, 3.18, 3.97, 4.76 and 6.35 mm");
}

TEST(PaperTests, APrintedSizeBuildsTheTable1Specimen) {
  const Scene base = parse_scene(default_shear_scene_text(), kDefaultSceneName);
  const Scene printed = paper_test_scene(base, kDefaultSceneName, 4.76, 280);
  const Scene exact = paper_test_scene(base, kDefaultSceneName, 4.7625, 280);
  EXPECT_EQ(printed.name, "d4.7625mm_280kPa");
  EXPECT_EQ(printed.name, exact.name);
  EXPECT_EQ(printed.apparatus_as<ShearBox>()->specimen.diameter, 4.7625e-3);
  EXPECT_EQ(printed.apparatus_as<ShearBox>()->specimen.layers, 4);
  EXPECT_EQ(printed.particles.size(), exact.particles.size());
  EXPECT_EQ(printed.apparatus_as<ShearBox>()->normal_stress, 280e3);
}

TEST(PaperTests, OtherSizesAreRefusedWithTheAcceptedOnes) {
  const Scene base = parse_scene(default_shear_scene_text(), kDefaultSceneName);
  try {
    paper_test_scene(base, kDefaultSceneName, 5, 280);
    FAIL() << "5 mm accepted as a Table 1 size";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.code, "out_of_range");
    EXPECT_EQ(e.field, "specimen.diameter");
    EXPECT_EQ(e.file, kDefaultSceneName);
    EXPECT_NE(e.message.find("2.38, 3.18, 3.97, 4.76 and 6.35 mm"), std::string::npos)
        << e.message;
    EXPECT_EQ(std::string(e.what()).find("assets/"), std::string::npos) << e.what();
  }
  // with its layers, any size is a test of the programme
  const Scene five = paper_test_scene(base, kDefaultSceneName, 5, 280, 4);
  EXPECT_EQ(five.apparatus_as<ShearBox>()->specimen.diameter, 5e-3);
}

}  // namespace
}  // namespace simsols
