// Pieces shared by the apparatus builders (shear_box.h, oedometer.h, triaxial.h): the
// rigid plates they are made of and the box material.
#pragma once

#include <string>
#include <vector>

#include "solver/scene/scene_check.h"

#include "solver/scene/scene.h"

namespace simsols {

// The apparatus' default material when the scene names none: steel. The
// paper gives no wall properties; restitution and friction are the glass
// values of its Table 2, so a glass-steel pair behaves as glass-glass but
// stiffer.
Material default_box_steel();

// A rectangle wall (a thin two-sided plate) centred at `centre`.
Wall rectangle_wall(const std::string& name, int material, const Vec3& centre, const Vec3& normal,
                    const Vec3& axis_u, double half_u, double half_v);

// A cuboid cell's six plates on [0, L] x [0, W] with the floor at z = 0,
// in the apparatus' wall order (OedometerWall, TriaxialWall): floor,
// <sides>_x0, <sides>_x1, <sides>_y0, <sides>_y1 (the side plates, `h`
// tall), platen (at platen_z, facing down). Each reaches `reach` past the
// cell's edges (0: exactly the cell's faces).
std::vector<Wall> cuboid_walls(const std::string& sides, int material, double L, double W,
                               double h, double platen_z, double reach);

// An apparatus' wall material: -1 becomes the scene's "steel", added (as
// default_box_steel) when the scene has none. False when `material` names
// no material of the scene.
bool resolve_wall_material(Scene& scene, int& material);

// Checks of an apparatus table's fields: a failure throws TableProblem with
// the field's dotted path under `table` ("oedometer.step_time"), which the
// builder returns as its SceneIssue.
struct TableProblem {
  SceneIssue issue;
};
struct TableCheck {
  std::string table;
  [[noreturn]] void fail(const std::string& code, const std::string& field,
                         const std::string& message) const;
  // Fails with "out_of_range ... allowed <allowed>" unless ok (and v finite).
  void require(bool ok, const std::string& field, double v, const std::string& allowed) const;
};

// Fails unless the scene has room for the apparatus' `added` walls
// (kMaxWalls in all; reported at the table's `length`).
void check_wall_room(const Scene& scene, int added, const TableCheck& check,
                     const std::string& apparatus);

// The servo settings every apparatus table has (servo_gain,
// servo_max_speed, servo_integral_time).
void check_servo_settings(const TableCheck& check, double gain, double max_speed,
                          double integral_time);

// The specimen's smallest and largest radius and the heights its beads
// reach. Fails at specimen.method when there are no beads or one is not
// inside the cell [0, length] x [0, width] x [0, inf), pressing into a
// wall by no more than kWallPress of its radius (named by `cell`:
// "box", "ring", ...).
// How far (a share of its radius) a bead may press into a cell wall.
inline constexpr double kWallPress = 0.05;
struct SpecimenExtent {
  double r_min, r_max, top, bottom;
};
SpecimenExtent measure_cell_specimen(const Scene& scene, double length, double width,
                                     const TableCheck& check, const std::string& cell);

// A size study's change to a scene not yet placed (registry.h `resize`):
// the cell's length and width times `across`, its specimen's layers times
// `height` (rounded, at least one). SceneError (out_of_range) naming the
// scene's cell when a factor is not in (0, 10].
void resize_cell(Scene& scene, double across, double height);

// The cell's narrowest inside width over its largest grain's diameter
// (the specimen's diameter, or its grading's d_max): the size ratio L/d
// ASTM D3080 and D7181 set a floor to.
double cell_size_ratio(const Scene& scene);

}  // namespace simsols
