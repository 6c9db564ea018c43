// Scene files: TOML in, TOML out, and the semantic validation of a Scene.
//
// Design. Reading a scene only reads; placing it is a step of its own:
//   1. read_scene() walks the TOML document with a small Reader that knows
//      the dotted path of the table it reads ("materials[1]"), refuses
//      unknown keys, wrong types and non-finite numbers, resolves material
//      names, and keeps [[generators]] and the apparatus table as
//      descriptions (Scene::generators, Scene::apparatus_pending); then
//      find_scene_issues() checks the values (ranges, unit normals). Fast:
//      nothing is placed, so `simsols run --explain` reads an 851 000-bead
//      scene at once.
//   2. place_scene() expands the generators (solver/scene/generators.h) and
//      builds the apparatus' walls and specimen (the registry's `build`),
//      then checks what needs every sphere (overlaps, the time-step limit).
//      Every front end reaches it through the one path from a scene to its
//      result (app/experiment/apparatus_run.h) or, to simulate a scene
//      directly, load_scene() / parse_scene(), which read and place.
// Both turn their issues into one SceneError, finding each line by looking
// the field path up in the document (an issue about a generated
// sphere or a clump member at its generator or clump); validate_scene()
// does the same without lines. Problems that let the reading go on are all
// reported at once: every unknown key and every value out of range, with
// the first problem that stops it (a missing field, a wrong type, an
// overlap). Every failure is a SceneError whose `code` is one of the stable
// identifiers listed in docs/scene-format.md, and whose `field` is the
// dotted TOML path.
//
// to_toml() writes every particle explicitly and every double in its shortest
// round-trip form, so parse_scene(to_toml(s)) reproduces a placed s bit for
// bit (except source_path / source_text, which describe where a scene came
// from).
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

// Reads a scene file without placing it (step 1). An unreadable file is a
// SceneError "io".
Scene read_scene(const std::string& path);
// Reads scene text; `path_for_messages` names the file in errors and is
// stored, with the text, in Scene::source_path / Scene::source_text.
Scene read_scene_text(std::string_view text, const std::string& path_for_messages);

// Places what a read scene describes (step 2); nothing when it is placed.
// SceneError naming the scene's file, line and field.
void place_scene(Scene& scene);

// read_scene / read_scene_text, then place_scene: a scene ready to simulate.
Scene load_scene(const std::string& path);
Scene parse_scene(std::string_view text, const std::string& path_for_messages);

// Serialises a placed scene (all particles explicit, no generators);
// std::logic_error for one not placed.
std::string to_toml(const Scene& scene);

}  // namespace simsols
