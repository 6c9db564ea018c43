// The lab's benches (lab_apparatus.h): one for each kind of the registry
// (solver/apparatus/registry.h), in its order, found by scene and by name;
// the built-in default scenes are of their bench's kind.
#include <gtest/gtest.h>

#include <string>

#include "app/lab/lab_apparatus.h"
#include "solver/apparatus/registry.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

TEST(LabBenches, OnePerRegistryKindInItsOrder) {
  const auto kinds = apparatus_kinds();
  const auto benches = lab_benches();
  ASSERT_EQ(benches.size(), kinds.size());
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    EXPECT_STREQ(benches[i].kind, kinds[i].name);
    EXPECT_EQ(lab_bench_index(kinds[i].name), int(i));
    if (!benches[i].default_scene_text) continue;  // the shear box: its preset
    const Scene s = parse_scene(benches[i].default_scene_text(), benches[i].default_scene_name);
    EXPECT_EQ(lab_bench_index(s), int(i)) << benches[i].kind;
  }
  EXPECT_EQ(lab_bench_index("periodic_cell"), -1);
  EXPECT_EQ(lab_kind_names(), apparatus_names("|"));
}

}  // namespace
}  // namespace simsols
