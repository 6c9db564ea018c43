// The reference paper's direct shear programme (its Table 1): five bead
// sizes, each in its number of layers, under 50, 160, 280 and 400 kPa.
// Shared by `simsols campaign` and the desktop lab's presets.
#pragma once

#include <functional>
#include <string>

#include "scene.h"

namespace simsols {

inline constexpr double kTable1SizesMm[] = {2.38125, 3.175, 3.96875, 4.7625, 6.35};
inline constexpr double kPaperStressesKpa[] = {50, 160, 280, 400};

// Table 1: bead diameter (mm) -> layers; 0 for other sizes.
int table1_layers(double d_mm);
// "d6.35mm_160kPa"
std::string paper_test_name(double d_mm, double s_kpa);

// One test of the programme from a base scene with a [shear_box]: its
// specimen replaced by `layers` layers (0 = Table 1) of d_mm beads, its
// normal stress set, the split and gap back to automatic; `adjust` may
// change it further before the box is built (precision, displacement).
// Throws SceneError naming `base_name` and the field.
Scene paper_test_scene(const Scene& base, const std::string& base_name, double d_mm,
                       double s_kpa, int layers = 0,
                       const std::function<void(Scene&)>& adjust = {});

// assets/scenes/shear_box.toml (the default experiment), embedded at build
// time so presets work from any directory.
const char* default_shear_scene_text();

}  // namespace simsols
