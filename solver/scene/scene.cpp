// Scene helpers: material lookup, effect slot names, the capillary bridge's
// reach and the distance from a point to a wall.
#include "solver/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

namespace simsols {

int Scene::material_index(const std::string& material_name) const {
  for (size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == material_name) return static_cast<int>(i);
  return -1;
}

double Scene::mass(const Particle& p) const {
  return materials[p.material].density * 4.0 / 3.0 * std::numbers::pi * p.radius * p.radius *
         p.radius;
}

double Scene::total_mass() const {
  double sum = 0;
  for (const Particle& p : particles) sum += mass(p);
  return sum;
}

const ApparatusCell* Scene::cell() const {
  return std::visit(
      [](const auto& a) -> const ApparatusCell* {
        if constexpr (std::is_base_of_v<ApparatusCell, std::decay_t<decltype(a)>>) return &a;
        return nullptr;
      },
      apparatus);
}

ApparatusCell* Scene::cell() {
  return const_cast<ApparatusCell*>(static_cast<const Scene*>(this)->cell());
}

const Specimen* Scene::specimen() const {
  const ApparatusCell* c = cell();
  return c ? &c->specimen : nullptr;
}

Specimen* Scene::specimen() {
  return const_cast<Specimen*>(static_cast<const Scene*>(this)->specimen());
}

bool Scene::has_gravity() const {
  return effects.gravity[0] != 0 || effects.gravity[1] != 0 || effects.gravity[2] != 0;
}

double capillary_rupture_distance(double liquid_volume, double contact_angle) {
  return (1 + 0.5 * contact_angle) * std::cbrt(liquid_volume);
}

double Scene::rupture_distance() const {
  if (effects.cohesion != CohesionModel::Capillary) return 0;
  const Capillary& c = effects.capillary;
  double s = capillary_rupture_distance(c.liquid_volume, c.contact_angle);
  for (const PairOverride& o : pair_overrides)
    s = std::max(s, capillary_rupture_distance(o.liquid_volume.value_or(c.liquid_volume),
                                               o.contact_angle.value_or(c.contact_angle)));
  return s;
}


Vec3 wall_closest_point(const Wall& w, const Vec3& p, const Vec3& x) {
  const Vec3 d = sub(x, p);
  if (w.shape == WallShape::Plane) return sub(x, scale(dot(d, w.normal), w.normal));
  const Vec3& u = w.axis_u;
  const Vec3 v = cross(w.normal, u);
  const double a = std::clamp(dot(d, u), -w.half_u, w.half_u);
  const double b = std::clamp(dot(d, v), -w.half_v, w.half_v);
  return {p[0] + a * u[0] + b * v[0], p[1] + a * u[1] + b * v[1], p[2] + a * u[2] + b * v[2]};
}

Wall tilted_wall(const Wall& w, double tilt) {
  if (tilt == 0) return w;
  const Vec3 v = cross(w.normal, w.axis_u);
  const double c = std::cos(tilt), s = std::sin(tilt);
  Wall t = w;
  t.normal = sub(scale(c, w.normal), scale(-s, cross(v, w.normal)));
  t.axis_u = sub(scale(c, w.axis_u), scale(-s, cross(v, w.axis_u)));
  return t;
}

double wall_distance(const Wall& w, const Vec3& p, const Vec3& x) {
  if (w.shape == WallShape::Plane) return dot(sub(x, p), w.normal);
  return norm(sub(x, wall_closest_point(w, p, x)));
}
}  // namespace simsols
