// The triaxial test's, the oedometer's and the periodic cell's default
// scenes, embedded at build time (assets/scenes/triaxial.toml,
// oedometer.toml, periodic_cell.toml) so the lab offers them
// from any directory; the shear box's is default_shear_scene_text()
// (paper_tests.h). The names below stand for them in error messages.
#pragma once

namespace simsols {

const char* default_triaxial_scene_text();
const char* default_oedometer_scene_text();
inline constexpr const char* kDefaultTriaxialSceneName = "built-in triaxial.toml";
inline constexpr const char* kDefaultOedometerSceneName = "built-in oedometer.toml";
const char* default_cell_scene_text();
inline constexpr const char* kDefaultCellSceneName = "built-in periodic_cell.toml";

}  // namespace simsols
