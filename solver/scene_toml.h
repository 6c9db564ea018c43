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
//      the issue's field path up in the document; validate_scene() does the
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

#include "scene.h"

namespace simsols {

// Reads and parses a scene file. An unreadable file is a SceneError "io".
Scene load_scene(const std::string& path);

// Parses scene text; `path_for_messages` names the file in errors and is
// stored, with the text, in Scene::source_path / Scene::source_text.
Scene parse_scene(std::string_view text, const std::string& path_for_messages);

// Serialises a scene (all particles explicit, no generators).
std::string to_toml(const Scene& scene);

// One semantic problem of a Scene: a SceneError without a location.
struct SceneIssue {
  std::string code;
  std::string field;  // dotted TOML path, e.g. "walls[0].normal"
  std::string message;
};

// The semantic problems of `scene`, empty when it is valid: every value out
// of range or not finite, or the first other problem (the checks stop there).
std::vector<SceneIssue> find_scene_issues(const Scene& scene);
// The first of them, or nullopt when the scene is valid.
std::optional<SceneIssue> find_scene_issue(const Scene& scene);

// Throws one SceneError (with `file`, line unknown) listing every issue.
void validate_scene(const Scene& scene, const std::string& file);

namespace detail {

// Shortest decimal text that parses back to exactly `v` ("0.1", "1e-05").
std::string format_number(double v);

// Uniform hash grid of spheres for O(1) neighbour queries; the cell size
// must be at least the largest diameter stored or queried.
class SphereGrid {
 public:
  explicit SphereGrid(double cell_size, size_t expected_spheres = 0);
  void insert(int index, const Vec3& center);
  // Calls f(index) for every stored sphere in the 27 cells around `center`.
  template <class F>
  void for_each_near(const Vec3& center, F&& f) const {
    const Cell c = cell_of(center);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells_.end()) continue;
          for (int i : it->second) f(i);
        }
  }

 private:
  struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell&) const = default;
  };
  struct CellHash {
    size_t operator()(const Cell& c) const;
  };
  Cell cell_of(const Vec3& p) const;
  double inv_cell_;
  std::unordered_map<Cell, std::vector<int>, CellHash> cells_;
};

}  // namespace detail
}  // namespace simsols
