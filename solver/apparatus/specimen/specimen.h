// A specimen in a rectangular cell, shared by every apparatus with one.
//
// The cell is [0, length] x [0, width] on the floor z = 0, open upward.
// Methods (Specimen::Method, scene.h):
//   Layers  the paper's preparation (its section 5 and Table 1): square
//           layers of floor(length/d) x floor(width/d) touching beads, the
//           row-to-wall clearance used either by shifting each layer as a
//           whole by a seeded random amount within it (Shift) or by
//           spreading it evenly between the rows (Spread); layers stacked
//           0.1 % of d apart so nothing overlaps before settling.
//   Pour    the same number of beads placed at random, without overlap, in
//           a column three specimen heights tall: rained in and settled.
//   Given   the scene's own particles (listed or generated): nothing placed.
// Placement is seeded and identical on every platform.
#pragma once

#include <optional>
#include <string>

#include "solver/scene/scene.h"
#include "solver/scene/scene_check.h"

namespace simsols {

// The square layer a cell allows for diameter d: floor(length/d) x
// floor(width/d) beads at a pitch of d (1 + 1e-6) (touching, never
// overlapping by round-off).
struct LayerGrid {
  int nx = 0, ny = 0;
  double pitch = 0;
};
LayerGrid layer_grid(double length, double width, double d);
int beads_per_layer(double length, double width, double d);

// Checks `specimen`'s settings and appends its beads to the scene; the
// first problem, its field under "<table>.specimen" (the apparatus' table).
std::optional<SceneIssue> place_specimen(Scene& scene, const Specimen& specimen,
                                         double length, double width, const std::string& table);

}  // namespace simsols
