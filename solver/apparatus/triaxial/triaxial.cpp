#include "solver/apparatus/triaxial/triaxial.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/cell/platen_servo.h"
#include "solver/apparatus/specimen/specimen.h"
#include "solver/apparatus/triaxial/membrane_cell.h"

namespace simsols {
namespace {

const TableCheck kCheck{"triaxial"};

void check_fields(const Triaxial& t, const Scene& scene) {
  kCheck.require(t.length > 0 && t.length < 10, "length", t.length, "(0, 10) m");
  kCheck.require(t.width > 0 && t.width < 10, "width", t.width, "(0, 10) m");
  kCheck.require(t.confining_stress > 0 && t.confining_stress <= 1e9, "confining_stress",
                 t.confining_stress, "(0, 1e9] Pa");
  kCheck.require(t.b_value >= 0 && t.b_value <= 1, "b_value", t.b_value, "[0, 1]");
  kCheck.require(t.axial_strain > 0 && t.axial_strain <= 0.5, "axial_strain", t.axial_strain,
                 "(0, 0.5]");
  kCheck.require(t.strain_rate >= 0 && t.strain_rate <= 1e4, "strain_rate", t.strain_rate,
                 "[0, 1e4] 1/s (0 = from inertial_number)");
  kCheck.require(t.inertial_number > 0 && t.inertial_number < 1, "inertial_number",
                 t.inertial_number, "(0, 1)");
  kCheck.require(t.settle_time >= 0 && t.settle_time <= 100, "settle_time", t.settle_time,
                 "[0, 100] s");
  kCheck.require(t.consolidate_time > 0 && t.consolidate_time <= 100, "consolidate_time",
                 t.consolidate_time, "(0, 100] s");
  check_servo_settings(kCheck, t.servo_gain, t.servo_max_speed, t.servo_integral_time);
  kCheck.require(t.rows >= 10 && t.rows <= 1000000, "rows", t.rows, "[10, 1000000]");
  kCheck.require(t.membrane_stiffness > 0 && t.membrane_stiffness <= 1e6, "membrane_stiffness",
                 t.membrane_stiffness, "(0, 1e6] N/m");
  kCheck.require(t.membrane_spacing >= 0.25 && t.membrane_spacing <= 1, "membrane_spacing", t.membrane_spacing,
                 "[0.25, 1] of the smallest bead's diameter");
  check_wall_room(scene, kTriaxialWalls, kCheck, "triaxial cell");
}

Wall servo_plate(Wall w, double max_speed) {
  w.servo.enabled = true;  // tuned and targeted by the loading programme
  w.servo.target_force = 1;
  w.servo.gain = 1;
  w.servo.max_speed = max_speed;
  return w;
}

void add_walls(Scene& scene, Triaxial& t, double top, double r_max) {
  const int m = t.wall_material;
  const double L = t.length, W = t.width;
  const double platen_z = top + 0.2 * r_max;
  const double h = platen_z + 2 * r_max;
  const double reach = 0.5 * std::max({L, W, h});  // past each edge
  t.first_wall = static_cast<int>(scene.walls.size());
  std::vector<Wall> w = cuboid_walls("side", m, L, W, h, platen_z, reach);
  for (int k = kTriX0; k <= kTriPlaten; ++k) w[k] = servo_plate(w[k], t.servo_max_speed);
  scene.walls.insert(scene.walls.end(), w.begin(), w.end());
}

// The membrane's beads, on a lattice of spacing s = membrane_spacing times
// the smallest bead's diameter, each of radius s: they overlap their
// neighbours by half, so the lattice has no holes until its bonds stretch
// by 40 % (with touching beads the grains of a specimen at 100 kPa parted
// a frictionless membrane and left it). Of the material named "membrane",
// else a copy of the specimen's whose density keeps the Rayleigh time step
// of the smallest bead (rho (r_min / s)^2). On a rounded rectangle s
// outside the footprint, rows about s apart over the height the specimen
// will have at kMembranePlannedPorosity. They wait, held, above the cell's plates
// until the programme wraps them about the consolidated specimen
// (triaxial_programme.cpp).
void add_membrane(Scene& scene, const Triaxial& t, const SpecimenExtent& e) {
  const double dm = 2 * e.r_min * t.membrane_spacing, rm = dm;  // spacing, radius
  int material = scene.material_index("membrane");  // a scene written back has it
  if (material < 0) {
    Material m = scene.materials[size_t(scene.particles.front().material)];
    m.name = "membrane";
    m.density *= (e.r_min / rm) * (e.r_min / rm);
    scene.materials.push_back(m);
    material = static_cast<int>(scene.materials.size()) - 1;
  }
  const double L = t.length, W = t.width;
  const double perimeter = 2 * (L + W) + 2 * std::numbers::pi * rm;
  double solids = 0;
  for (const Particle& p : scene.particles) solids += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius, 3);
  const double height = solids / (L * W * (1 - kMembranePlannedPorosity));
  Membrane& mem = scene.membrane;
  mem.first = static_cast<int>(scene.particles.size());
  mem.cols = std::max(8, static_cast<int>(std::lround(perimeter / dm)));
  mem.rows = std::max(3, static_cast<int>(std::lround((height - 2 * rm) / dm)) + 1);
  mem.stiffness = t.membrane_stiffness;
  mem.platen_wall = t.first_wall + kTriPlaten;
  double park = e.top + 2 * height;  // above every plate, out of reach
  for (const Wall& w : scene.walls) {
    const Vec3 v = cross(w.normal, w.axis_u);
    park = std::max(park, w.point[2] + std::fabs(w.axis_u[2]) * w.half_u + std::fabs(v[2]) * w.half_v);
  }
  park += 2 * rm + e.r_max;
  const std::vector<Vec3> ring = membrane_ring(0, L, 0, W, rm, mem.cols);
  for (int r = 0; r < mem.rows; ++r)
    for (const Vec3& x : ring) {
      Particle p;
      p.material = material;
      p.radius = rm;
      p.position = {x[0], x[1], park + r * dm};
      scene.particles.push_back(p);
    }
}

void build(Scene& scene) {
  Triaxial& t = *scene.apparatus_as<Triaxial>();
  check_fields(t, scene);
  if (auto issue = place_specimen(scene, t.specimen, t.length, t.width, "triaxial"))
    throw TableProblem{*issue};
  const SpecimenExtent e = measure_cell_specimen(scene, t.length, t.width, kCheck, "cell");
  if (!resolve_wall_material(scene, t.wall_material))
    kCheck.fail("unknown_material", "wall_material", "the plates' material does not exist");
  add_walls(scene, t, e.top, e.r_max);
  if (t.cell == Triaxial::Cell::Membrane) add_membrane(scene, t, e);
}

}  // namespace

std::optional<SceneIssue> build_triaxial(Scene& scene) {
  if (!scene.apparatus_as<Triaxial>()) return std::nullopt;
  try {
    build(scene);
  } catch (const TableProblem& p) {
    return p.issue;
  }
  return std::nullopt;
}

double triaxial_inertial_number(double strain_rate, double d, double density, double p) {
  return strain_rate * d * std::sqrt(density / p);
}

double triaxial_strain_rate(double inertial_number, double d, double density, double p) {
  return inertial_number / d * std::sqrt(p / density);
}


double triaxial_expected_time(const Scene& s) {
  const Triaxial& t = *s.apparatus_as<Triaxial>();
  const SpecimenStats b = specimen_stats(s, t.wall_material);
  const double rate = t.strain_rate > 0 ? t.strain_rate
                                        : triaxial_strain_rate(t.inertial_number, b.diameter, b.density,
                                                               t.confining_stress);
  return 0.3 * (t.settle_time + t.consolidate_time) + t.axial_strain / rate;
}
}  // namespace simsols
