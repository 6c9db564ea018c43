// The triaxial test's and the oedometer's default scenes, embedded at build
// time (assets/scenes/triaxial.toml, oedometer.toml) so the lab offers them
// from any directory; the shear box's is default_shear_scene_text()
// (paper_tests.h). The names below stand for them in error messages.
#pragma once

namespace simsols {

const char* default_triaxial_scene_text();
const char* default_oedometer_scene_text();
inline constexpr const char* kDefaultTriaxialSceneName = "built-in triaxial.toml";
inline constexpr const char* kDefaultOedometerSceneName = "built-in oedometer.toml";

}  // namespace simsols
