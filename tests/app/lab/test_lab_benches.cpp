// The lab's benches (lab_apparatus.h): of the registry's kinds
// (solver/apparatus/registry.h), in its order, found by scene and by name;
// the built-in default scenes are of their bench's kind.
#include <gtest/gtest.h>

#include <string>

#include "app/lab/lab_apparatus.h"
#include "solver/apparatus/registry.h"
#include "solver/io/scene_toml.h"

namespace simsols {
namespace {

// Each bench is of a registry kind, at most one per kind, in the
// registry's order (a kind without one, a headless apparatus, is refused by
// the lab by name); the four of today have one each.
TEST(LabBenches, OnePerRegistryKindInItsOrder) {
  const auto kinds = apparatus_kinds();
  const auto benches = lab_benches();
  std::size_t k = 0;
  for (std::size_t i = 0; i < benches.size(); ++i) {
    while (k < kinds.size() && std::string(kinds[k].name) != benches[i].kind) ++k;
    ASSERT_LT(k, kinds.size()) << benches[i].kind << " is not a registry kind, or out of its order";
    EXPECT_EQ(lab_bench_index(kinds[k].name), int(i));
    ++k;
    if (!benches[i].default_scene_text) continue;  // the shear box: its preset
    const Scene s = parse_scene(benches[i].default_scene_text(), benches[i].default_scene_name);
    EXPECT_EQ(lab_bench_index(s), int(i)) << benches[i].kind;
  }
  EXPECT_EQ(benches.size(), 4u);
  EXPECT_EQ(lab_bench_index("periodic_cell"), 3);
  EXPECT_EQ(lab_bench_index("ring_shear"), -1);
  EXPECT_EQ(lab_kind_names(), "shear_box|oedometer|triaxial|periodic_cell");
}

}  // namespace
}  // namespace simsols
