#include "solver/apparatus/cell/cell_walls.h"

#include <algorithm>
#include <cmath>

#include "solver/apparatus/specimen/grading.h"
#include "solver/common/errors.h"
#include "solver/common/number_text.h"

namespace simsols {

Material default_box_steel() { return {"steel", 200e9, 0.3, 7850, 0.87, 0.02, 5e-5}; }

Wall rectangle_wall(const std::string& name, int material, const Vec3& centre, const Vec3& normal,
                    const Vec3& axis_u, double half_u, double half_v) {
  Wall w;
  w.name = name;
  w.shape = WallShape::Rectangle;
  w.material = material;
  w.point = centre;
  w.normal = normal;
  w.axis_u = axis_u;
  w.half_u = half_u;
  w.half_v = half_v;
  return w;
}

std::vector<Wall> cuboid_walls(const std::string& sides, int m, double L, double W, double h,
                               double platen_z, double reach) {
  const Vec3 ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};
  const double hu = L / 2 + reach, hv = W / 2 + reach, hz = h / 2 + reach;
  return {rectangle_wall("floor", m, {L / 2, W / 2, 0}, ez, ex, hu, hv),
          rectangle_wall(sides + "_x0", m, {0, W / 2, h / 2}, ex, ey, hv, hz),
          rectangle_wall(sides + "_x1", m, {L, W / 2, h / 2}, {-1, 0, 0}, ey, hv, hz),
          rectangle_wall(sides + "_y0", m, {L / 2, 0, h / 2}, ey, ex, hu, hz),
          rectangle_wall(sides + "_y1", m, {L / 2, W, h / 2}, {0, -1, 0}, ex, hu, hz),
          rectangle_wall("platen", m, {L / 2, W / 2, platen_z}, {0, 0, -1}, ex, hu, hv)};
}

bool resolve_wall_material(Scene& scene, int& material) {
  if (material < 0) {
    material = scene.material_index("steel");
    if (material < 0) {
      scene.materials.push_back(default_box_steel());
      material = static_cast<int>(scene.materials.size()) - 1;
    }
  }
  return material < static_cast<int>(scene.materials.size());
}

void TableCheck::fail(const std::string& code, const std::string& field,
                      const std::string& message) const {
  throw TableProblem{{code, table + "." + field, message}};
}

void TableCheck::require(bool ok, const std::string& field, double v,
                         const std::string& allowed) const {
  if (!std::isfinite(v)) fail("not_finite", field, shortest_number(v) + " is not a finite number");
  if (!ok) fail("out_of_range", field, shortest_number(v) + " is out of range, allowed " + allowed);
}

void check_wall_room(const Scene& scene, int added, const TableCheck& check,
                     const std::string& apparatus) {
  if (scene.walls.size() + added > kMaxWalls)
    check.fail("out_of_range", "length",
               "the " + apparatus + " adds " + std::to_string(added) + " walls to the scene's " +
                   std::to_string(scene.walls.size()) + "; at most " + std::to_string(kMaxWalls) +
                   " walls are allowed");
}

void check_servo_settings(const TableCheck& check, double gain, double max_speed,
                          double integral_time) {
  check.require(gain >= 0, "servo_gain", gain, "[0, inf) m/(s N) (0 = automatic)");
  check.require(max_speed > 0 && max_speed <= 10, "servo_max_speed", max_speed, "(0, 10] m/s");
  check.require(integral_time >= 0, "servo_integral_time", integral_time,
                "[0, inf) s (0 = automatic)");
}

SpecimenExtent measure_cell_specimen(const Scene& scene, double length, double width,
                                     const TableCheck& check, const std::string& cell) {
  if (scene.particles.empty())
    check.fail("out_of_range", "specimen.method", "the specimen has no beads (the scene lists none)");
  SpecimenExtent e{scene.particles[0].radius, 0, 0, 1e300};
  for (const Particle& p : scene.particles) {
    const Vec3& x = p.position;
    e.r_min = std::min(e.r_min, p.radius);
    e.r_max = std::max(e.r_max, p.radius);
    e.top = std::max(e.top, x[2] + p.radius);
    e.bottom = std::min(e.bottom, x[2] - p.radius);
    // a settled bead presses into the walls it rests on (~1e-4 of its
    // radius): a given specimen saved at rest must load again
    const double r = (1 - kWallPress) * p.radius;
    const bool inside = x[0] >= r && x[0] <= length - r && x[1] >= r && x[1] <= width - r && x[2] >= r;
    if (!inside)
      check.fail("out_of_range", "specimen.method",
                 "a bead at (" + shortest_number(x[0]) + ", " + shortest_number(x[1]) + ", " +
                     shortest_number(x[2]) + ") is not inside the " + cell +
                     " [0, length] x [0, width] x [0, inf) (a bead may press into a wall by up to "
                     "5 % of its radius)");
  }
  return e;
}

void resize_cell(Scene& scene, double across, double height) {
  ApparatusCell* cell = scene.cell();
  const std::string file = scene.source_path.empty() ? scene.name : scene.source_path;
  if (!cell) throw SceneError("no_apparatus", file, 0, "apparatus", "no cell to resize");
  for (double f : {across, height})
    if (!(f > 0 && f <= 10))
      throw SceneError("out_of_range", file, 0, "size factor",
                       shortest_number(f) + " is out of range, allowed (0, 10]");
  cell->length *= across;
  cell->width *= across;
  cell->specimen.layers = std::max(1, static_cast<int>(std::lround(cell->specimen.layers * height)));
}

double cell_size_ratio(const Scene& scene) {
  const ApparatusCell* cell = scene.cell();
  if (!cell || !(cell->specimen.diameter > 0)) return 0;
  double d = cell->specimen.diameter;
  if (cell->specimen.grading.law != Grading::Law::Single)
    d = grading_curve(cell->specimen.grading, d).size.back();
  return std::min(cell->length, cell->width) / d;
}

}  // namespace simsols
