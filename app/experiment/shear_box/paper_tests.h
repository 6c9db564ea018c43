// The reference paper's direct shear programme (its Table 1): five bead
// sizes, each in its number of layers, under 50, 160, 280 and 400 kPa.
// Shared by `simsols campaign` and the desktop lab's presets.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "solver/scene/scene.h"

namespace simsols {

inline constexpr double kTable1SizesMm[] = {2.38125, 3.175, 3.96875, 4.7625, 6.35};
inline constexpr double kPaperStressesKpa[] = {50, 160, 280, 400};

// The Table 1 size that `d_mm` names: the nearest one within 0.5 %, so the
// sizes as the docs and the lab's panel print them (2.38, 3.18, 3.97, 4.76)
// name the exact ones (2.38125, 3.175, 3.96875, 4.7625); nullopt otherwise.
std::optional<double> nearest_table1_size(double d_mm);
// Table 1: bead diameter (mm, as nearest_table1_size reads it) -> layers; 0
// for other sizes.
int table1_layers(double d_mm);
// "2.38, 3.18, 3.97, 4.76 and 6.35 mm": the sizes as the panel prints them.
std::string table1_sizes_text();
// "d6.35mm_160kPa"
std::string paper_test_name(double d_mm, double s_kpa);

// One test of the programme from a base scene with a [shear_box]: its
// specimen replaced by `layers` layers of d_mm beads (layers = 0: Table 1's
// layers, and d_mm read as the Table 1 size it names), its
// normal stress set, the split back to automatic and the gap the same share
// of the diameter as the base's (0.2 d by default); `adjust` may
// change it further before the box is built (precision, displacement).
// Throws SceneError naming `base_name` and the field.
Scene paper_test_scene(const Scene& base, const std::string& base_name, double d_mm,
                       double s_kpa, int layers = 0,
                       const std::function<void(Scene&)>& adjust = {});

// assets/scenes/shear_box.toml (the default experiment), embedded at build
// time so presets work from any directory; kDefaultSceneName names it in
// messages.
const char* default_shear_scene_text();
inline constexpr const char* kDefaultSceneName = "built-in shear_box.toml";

// That scene as the base of the tests a programme plans (campaigns, the
// studies, the lab's presets). Its ParaView frames every output.
// dump_interval are the default experiment's own: a programme's tests write
// their last state only, or a campaign of the 2.38 mm beads would write
// hundreds of MB of frames nobody asked for.
Scene default_shear_base();

}  // namespace simsols
