#include "solver/apparatus/periodic_cell/periodic_cell.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "solver/common/number_text.h"
#include "solver/core/observe.h"
#include "solver/scene/generators.h"

namespace simsols {
namespace {

std::optional<SceneIssue> issue(const std::string& field, double value, const std::string& allowed) {
  return SceneIssue{"out_of_range", "periodic_cell." + field,
                    shortest_number(value) + " is out of range, allowed " + allowed};
}

std::optional<SceneIssue> check(const PeriodicCell& c, const Scene& scene) {
  if (c.particles < 8) return issue("particles", c.particles, "[8, 10000000]");
  if (!(c.diameter > 0)) return issue("diameter", c.diameter, "(0, inf) m");
  if (!(c.size_spread >= 0 && c.size_spread < 1)) return issue("size_spread", c.size_spread, "[0, 1)");
  if (c.material < 0 || c.material >= int(scene.materials.size()))
    return issue("material", c.material, "a material of the scene");
  if (!(c.start_solid_fraction > 0 && c.start_solid_fraction <= 0.4))
    return issue("start_solid_fraction", c.start_solid_fraction, "(0, 0.4]");
  if (!(c.preparation_friction >= 0)) return issue("preparation_friction", c.preparation_friction, "[0, inf)");
  if (!(c.preparation_restitution > 0 && c.preparation_restitution <= 1))
    return issue("preparation_restitution", c.preparation_restitution, "(0, 1]");
  if (c.preparation_rolling_friction && !(*c.preparation_rolling_friction >= 0))
    return issue("preparation_rolling_friction", *c.preparation_rolling_friction, "[0, inf) m");
  if (!(c.pressure > 0)) return issue("pressure", c.pressure, "(0, inf) Pa");
  if (!(c.inertial_number > 0 && c.inertial_number <= 1))
    return issue("inertial_number", c.inertial_number, "(0, 1]");
  if (!(c.compression_inertial_number > 0 && c.compression_inertial_number <= 1))
    return issue("compression_inertial_number", c.compression_inertial_number, "(0, 1]");
  if (!(c.shear_strain > 0)) return issue("shear_strain", c.shear_strain, "(0, inf)");
  if (!(c.axial_strain > 0 && c.axial_strain < 0.9)) return issue("axial_strain", c.axial_strain, "(0, 0.9)");
  if (!(c.vertical_stress == 0 || c.vertical_stress > c.pressure))
    return issue("vertical_stress", c.vertical_stress, "0 (4 x pressure) or above pressure, Pa");
  if (!(c.row_strain > 0)) return issue("row_strain", c.row_strain, "(0, inf)");
  return std::nullopt;
}

// The gas: random sequential insertion into a cube of the solid fraction
// asked (the whole cell's a little lower: below).
std::optional<SceneIssue> place_gas(Scene& scene, const PeriodicCell& c) {
  const double r_min = 0.5 * c.diameter * (1 - 0.5 * c.size_spread);
  const double r_max = 0.5 * c.diameter * (1 + 0.5 * c.size_spread);
  // E[r^3] for r uniform in [r_min, r_max]
  const double r3 = c.size_spread > 0 ? (std::pow(r_max, 4) - std::pow(r_min, 4)) / (4 * (r_max - r_min))
                                      : r_min * r_min * r_min;
  const double solids = c.particles * 4.0 / 3.0 * std::numbers::pi * r3;
  const double side = std::cbrt(solids / c.start_solid_fraction);
  Generator g;
  g.type = Generator::Type::Random;
  g.material = c.material;
  g.min = {0, 0, 0};
  g.max = {side, side, side};
  g.seed = static_cast<std::uint64_t>(c.seed);
  g.radius_min = r_min;
  g.radius_max = r_max;
  g.count = c.particles;
  scene.generators.push_back(g);
  if (std::optional<SceneIssue> bad = expand_generators(scene)) {
    bad->field = "periodic_cell.start_solid_fraction";
    return bad;
  }
  // the cell is a largest diameter wider than the box the spheres fill: no
  // sphere touches another's image at the start
  const double cell = side + 2 * r_max;
  PeriodicBox box;
  box.edges = {cell, 0, 0, 0, cell, 0, 0, 0, cell};
  box.preparation_friction = c.preparation_friction;
  box.preparation_restitution = c.preparation_restitution;
  scene.periodic = box;
  return std::nullopt;
}

}  // namespace

std::optional<SceneIssue> build_periodic_cell(Scene& scene) {
  const PeriodicCell& c = *scene.apparatus_as<PeriodicCell>();
  if (std::optional<SceneIssue> bad = check(c, scene)) return bad;
  scene.effects.gravity = {0, 0, 0};
  if (c.given) {
    if (!(det3(c.edges) > 0) || !upper_triangular(c.edges))
      return SceneIssue{"out_of_range", "periodic_cell.edges",
                        "the cell's edges must be upper triangular with a positive volume"};
    scene.periodic = PeriodicBox{c.edges, {0, 0, 0}, c.preparation_friction, c.preparation_restitution};
    return std::nullopt;
  }
  return place_gas(scene, c);
}

CellMeasure measure_cell(Simulation& sim) {
  const Model& m = sim.model();
  State& s = sim.state();
  const std::vector<ContactForce> contacts = contact_list(m, s);
  const std::vector<double> pos = read_reals(m, s.pos, size_t(s.n) * 4);
  const std::vector<double> vel = read_reals(m, s.vel, size_t(s.n) * 4);
  const Mat3& h = s.cell_now.h;
  CellMeasure out;
  out.volume = det3(h);
  std::vector<int> touching(s.n, 0);
  for (const ContactForce& c : contacts) {
    const Vec3 xa{pos[4 * c.a], pos[4 * c.a + 1], pos[4 * c.a + 2]};
    const Vec3 xb{pos[4 * c.b], pos[4 * c.b + 1], pos[4 * c.b + 2]};
    const Vec3 l = min_image(h, sub(xb, xa));
    const double len = norm(l);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        out.stress[3 * a + b] -= c.force[a] * l[b];
        out.fabric[3 * a + b] += l[a] * l[b] / (len * len);
      }
    ++touching[c.a];
    ++touching[c.b];
  }
  out.contacts = static_cast<int>(contacts.size());
  for (double& x : out.stress) x /= out.volume;
  if (!contacts.empty())
    for (double& x : out.fabric) x /= double(contacts.size());
  double solids = 0;
  int backbone = 0, backbone_ends = 0;
  for (int i = 0; i < s.n; ++i) {
    const double r = pos[4 * i + 3], mass = vel[4 * i + 3];
    solids += 4.0 / 3.0 * std::numbers::pi * r * r * r;
    const Vec3 u{vel[4 * i], vel[4 * i + 1], vel[4 * i + 2]};
    out.kinetic += 0.5 * mass * dot(u, u);
    if (touching[i] >= 2) ++backbone, backbone_ends += touching[i];
  }
  out.solid_fraction = solids / out.volume;
  out.coordination = s.n > 0 ? 2.0 * contacts.size() / s.n : 0;
  out.coordination_backbone = backbone > 0 ? double(backbone_ends) / backbone : 0;
  return out;
}


double periodic_cell_expected_time(const Scene& s) {
  const PeriodicCell& c = *s.apparatus_as<PeriodicCell>();
  const double rho = s.materials.at(c.material).density;
  const double scale = std::sqrt(c.pressure / rho) / c.diameter;
  double seconds = 2 * std::log(0.6 / c.start_solid_fraction) / 3 / (c.compression_inertial_number * scale);
  if (c.test == PeriodicCell::Test::SimpleShear) seconds += c.shear_strain / (c.inertial_number * scale);
  if (c.test == PeriodicCell::Test::AxialCompression) seconds += c.axial_strain / (c.inertial_number * scale);
  if (c.test == PeriodicCell::Test::Oedometric)
    seconds += kOedometricTravelEstimate / (c.inertial_number * scale);
  return seconds;
}
}  // namespace simsols
