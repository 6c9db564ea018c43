// A scene file with some of its values replaced, by dotted key: how a
// calibration sets the parameters it fits, a target's own settings and a
// replicate's seed on the scene of a test, without knowing the scene's
// tables.
//
// A key is a dotted path of the scene's TOML: "periodic_cell.seed",
// "triaxial.specimen.preparation.void_ratio". Where a component meets an
// array of tables ([[materials]], [[grains]]), the next one is the name of
// the entry: "materials.sand.sliding_friction". Every table on the path
// must exist; the last key is set or added. The scene is then read as the
// scene reader reads any file, so a value out of its range is reported
// with the field's name as usual.
#pragma once

#include <toml++/toml.h>

#include <string>
#include <utility>
#include <vector>

#include "solver/scene/scene.h"

namespace simsols {

struct SceneValue {
  std::string key;
  double value = 0;
  bool integer = false;  // written as a TOML integer (a seed)
};

// The values one test of a calibration or a prediction runs with: `first`,
// then `then` (a key in both takes then's value), then the specimen's seed
// under the kind's `seed_key` when `seed` > 0.
using KeyValues = std::vector<std::pair<std::string, double>>;
std::vector<SceneValue> test_values(const KeyValues& first, const KeyValues& then,
                                    const char* seed_key, int seed);

// The TOML file at `path`; SceneError naming its line when it is not TOML
// (the calibration's, prediction's and calibrated files read it too).
toml::table parse_toml_file(const std::string& path);

// The scene at `path` with `values` set, read (not placed). SceneError
// naming `path` and the key when a table on a key's path is missing.
Scene scene_with(const std::string& path, const std::vector<SceneValue>& values);

// The TOML text of the scene at `path` with `values` set (what scene_with
// reads): for a run's folder.
std::string scene_text_with(const std::string& path, const std::vector<SceneValue>& values);

// A calibration's material on a scene already read (the lab's): each value
// whose key names a field of one of the scene's materials
// ("materials.<name>.<field>": young_modulus, poisson_ratio, density,
// restitution, sliding_friction, rolling_friction) is set on it. Returns
// the keys of the other values, which are not set (a key of another
// table, a material the scene does not have).
std::vector<std::string> set_material_values(
    Scene& scene, const std::vector<std::pair<std::string, double>>& values);

}  // namespace simsols
