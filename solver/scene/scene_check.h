// The semantic rules of a Scene, shared by scenes built in code and scenes
// loaded from TOML: ranges, unit normals, overlaps, the time-step limit.
//
// Values out of range or not finite are all reported at once; any other
// problem (an overlap, a wall crossing another) ends the checks there. An
// issue names its field by the dotted TOML path ("walls[0].normal"), so the
// loader can point at the line and a scene built in code at the member.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "solver/scene/scene.h"

namespace simsols {

// One semantic problem of a Scene: a SceneError without a location.
struct SceneIssue {
  std::string code;
  std::string field;  // dotted TOML path, e.g. "walls[0].normal"
  std::string message;
};

// The semantic problems of `scene`, empty when it is valid: every value out
// of range or not finite, or the first other problem (the checks stop there).
// A scene not yet placed (Scene::placed) is checked as far as it goes: its
// values, not overlaps nor the time step, which need every sphere.
std::vector<SceneIssue> find_scene_issues(const Scene& scene);
// The first of them, or nullopt when the scene is valid.
std::optional<SceneIssue> find_scene_issue(const Scene& scene);

// Throws one SceneError (with `file`, line unknown) listing every issue.
void validate_scene(const Scene& scene, const std::string& file);

}  // namespace simsols
