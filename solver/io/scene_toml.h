// Scene files: TOML in, TOML out, and the semantic validation of a Scene.
//
// Design. Loading a scene is two passes:
//   1. parse_scene() walks the TOML document with a small Reader that knows
//      the dotted path of the table it reads ("materials[1]"), refuses
//      unknown keys, wrong types and non-finite numbers, resolves material
//      names and expands [[generators]] into particles.
//   2. find_scene_issues() checks the rules shared with scenes built in code
//      (ranges, unit normals, overlaps, the time-step limit). parse_scene()
//      turns its issues into one SceneError, finding each line by looking
//      the field path up in the document; validate_scene() does the
//      same without lines.
// Problems that let the reading go on are all reported at once: every
// unknown key (pass 1) and every value out of range (pass 2), with the first
// problem that stops it (a missing field, a wrong type, an overlap).
// Every failure is a SceneError whose `code` is one of the stable identifiers
// listed in docs/scene-format.md, and whose `field` is the dotted TOML path.
//
// to_toml() writes every particle explicitly and every double in its shortest
// round-trip form, so parse_scene(to_toml(s)) reproduces s bit for bit
// (except source_path / source_text, which describe where a scene came from).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

// Reads and parses a scene file. An unreadable file is a SceneError "io".
Scene load_scene(const std::string& path);

// Parses scene text; `path_for_messages` names the file in errors and is
// stored, with the text, in Scene::source_path / Scene::source_text.
Scene parse_scene(std::string_view text, const std::string& path_for_messages);

// Serialises a scene (all particles explicit, no generators).
std::string to_toml(const Scene& scene);

}  // namespace simsols
