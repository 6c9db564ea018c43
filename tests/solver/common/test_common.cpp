// The shared helpers of solver/common: numbers as text that read back
// exactly (number_text.h), "did you mean" (did_you_mean.h), and the error
// types' messages (errors.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "solver/common/did_you_mean.h"
#include "solver/common/errors.h"
#include "solver/common/number_text.h"

namespace simsols {
namespace {

TEST(NumberText, ShortestTextReadsBackToTheSameBits) {
  const std::vector<double> values = {0.1, 1e-5, 2.38125e-3, 6.3e10, 1.0 / 3.0, -0.0, 5e-324,
                                      std::numeric_limits<double>::max(), 160e3, 0.87};
  for (double v : values) {
    const std::string text = shortest_number(v);
    const double back = std::strtod(text.c_str(), nullptr);
    EXPECT_EQ(std::signbit(back), std::signbit(v)) << text;
    EXPECT_EQ(back, v) << text;
  }
  EXPECT_EQ(shortest_number(0.1), "0.1");
  EXPECT_EQ(shortest_number(1e-5), "1e-05");
  EXPECT_EQ(shortest_number(160000), "160000");
}

TEST(DidYouMean, SuggestsTheClosestNameWhenCloseEnough) {
  EXPECT_EQ(edit_distance("density", "densty"), 1u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  const std::vector<std::string> keys = {"density", "young_modulus", "poisson_ratio"};
  EXPECT_EQ(did_you_mean("densty", keys), " (did you mean 'density'?)");
  EXPECT_EQ(did_you_mean("poisson", keys), "") << "6 edits from poisson_ratio: too far";
  EXPECT_EQ(did_you_mean("colour", keys), "");
}

TEST(Errors, UsageErrorNamesTheFlagOnTheCommandLine) {
  const UsageError e("out_of_range", "--jobs", "17 is out of range, allowed [1, 16]");
  EXPECT_EQ(e.file, "command line");
  EXPECT_EQ(e.field, "--jobs");
  EXPECT_EQ(e.code, "out_of_range");
  EXPECT_NE(std::string(e.what()).find("--jobs"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("allowed [1, 16]"), std::string::npos) << e.what();
  const InputError& base = e;  // main() maps every InputError to exit status 2
  EXPECT_EQ(base.problems.size(), 1u);
}

TEST(Errors, SceneErrorListsEveryProblemWithTheFileOnce) {
  const SceneError e("scene.toml", {{"unknown_key", 3, "materials[0].densty", "unknown key"},
                                    {"out_of_range", 7, "numerics.dt", "-1 is out of range"}});
  const std::string what = e.what();
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.field, "materials[0].densty");
  EXPECT_EQ(what.find("scene.toml"), what.rfind("scene.toml")) << "the file named once: " << what;
  EXPECT_NE(what.find("numerics.dt"), std::string::npos) << what;
}

}  // namespace
}  // namespace simsols
