#include "solver/apparatus/cell_walls.h"

#include <cmath>

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

}  // namespace simsols
