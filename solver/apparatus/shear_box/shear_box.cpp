#include "solver/apparatus/shear_box/shear_box.h"

#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/specimen/specimen.h"

#include <algorithm>
#include <cmath>

#include "solver/common/number_text.h"
#include "solver/scene/clump.h"

namespace simsols {
namespace {

std::string num(double v) { return shortest_number(v); }

const TableCheck kCheck{"shear_box"};

void check_box(const ShearBox& b, const Scene& scene) {
  kCheck.require(b.length > 0 && b.length < 10, "length", b.length, "(0, 10) m");
  kCheck.require(b.width > 0 && b.width < 10, "width", b.width, "(0, 10) m");
  kCheck.require(b.normal_stress > 0 && b.normal_stress <= 1e9, "normal_stress", b.normal_stress,
          "(0, 1e9] Pa");
  kCheck.require(b.shear_speed >= 0 && b.shear_speed <= 10, "shear_speed", b.shear_speed,
          "[0, 10] m/s (0 = from inertial_number)");
  kCheck.require(b.inertial_number > 0 && b.inertial_number < 1, "inertial_number", b.inertial_number,
          "(0, 1)");
  kCheck.require(b.shear_displacement > 0 && b.shear_displacement <= 0.5 * b.length,
          "shear_displacement", b.shear_displacement, "(0, " + num(0.5 * b.length) + "] m (half the length)");
  kCheck.require(b.platen_mass >= 0 && b.platen_mass <= 1e4, "platen_mass", b.platen_mass,
          "[0, 1e4] kg (0 = automatic)");
  check_servo_settings(kCheck, b.servo_gain, b.servo_max_speed, b.servo_integral_time);
  kCheck.require(b.upper_half_weight >= 0 && b.upper_half_weight <= 1e4, "upper_half_weight",
                 b.upper_half_weight, "[0, 1e4] N");
  if (b.cap == ShearBox::Cap::Tilting && b.loading != ShearBox::Loading::DeadWeight)
    kCheck.fail("conflicting_keys", "cap",
                "\"tilting\" needs loading = \"dead_weight\" (a servo-held platen has no mass to "
                "turn); allowed with loading = \"servo\": \"held\"");
  kCheck.require(b.settle_time >= 0 && b.settle_time <= 100, "settle_time", b.settle_time, "[0, 100] s");
  kCheck.require(b.consolidate_time > 0 && b.consolidate_time <= 100, "consolidate_time",
          b.consolidate_time, "(0, 100] s");
  kCheck.require(b.rows >= 10 && b.rows <= 1000000, "rows", b.rows, "[10, 1000000]");
  kCheck.require(b.split_height >= 0, "split_height", b.split_height, "[0, inf) m (0 = mid-height)");
  kCheck.require(b.gap >= 0, "gap", b.gap, "[0, inf) m (0 = automatic)");
  check_wall_room(scene, kShearBoxWalls, kCheck, "shear box");
}

// The automatic split height (split_height = 0).
double default_split_height(const Scene& scene, const ShearBox& b, const SpecimenExtent& e) {
  const Specimen& s = b.specimen;
  if (s.method == Specimen::Method::Layers) {
    // Between the two layers nearest mid-height (the lower half holds
    // floor(layers/2)), at the height they reach once every layer has
    // nested into the one below as far as the row-wall clearance lets it
    // shift (at most half a diameter each way: d/sqrt(2) apart).
    const double d = s.diameter;
    const LayerGrid grid = layer_grid(b, d);
    const double cx = std::min(0.5 * d, b.length - grid.nx * d);
    const double cy = std::min(0.5 * d, b.width - grid.ny * d);
    const double spacing = s.clearance == Specimen::Clearance::Spread
                               ? d
                               : std::sqrt(d * d - cx * cx - cy * cy);
    const int lower = std::max(1, s.layers / 2);
    return s.layers == 1 ? d / 2 : d / 2 + (lower - 0.5) * spacing;
  }
  // Mid-height of the given beads, or of a pour once settled: its solid
  // volume (a clump's overlaps counted once) at the tamping target's void
  // ratio, or at a solid fraction of 0.6.
  const double height = e.top - e.bottom;
  if (s.method == Specimen::Method::Pour) {
    double volume = 0;
    for (const double v : solid_volumes(scene)) volume += v;
    const double fraction = s.preparation.void_ratio ? 1 / (1 + *s.preparation.void_ratio) : 0.6;
    return e.bottom + 0.5 * volume / (fraction * b.length * b.width);
  }
  return e.bottom + 0.5 * height;
}

// The twelve walls (shear_box.h), from b.first_wall on.
void add_walls(Scene& scene, ShearBox& b, const SpecimenExtent& e) {
  // Geometry: plates reach a little past the corners; the upper half is
  // tall enough for the platen's start and a generous dilation.
  const int m = b.wall_material, insert = b.insert_material;
  const double L = b.length, W = b.width, zs = b.split_height, g = b.gap;
  const double platen_z = e.top + 0.1 * 2 * e.r_max;
  const double upper_top = platen_z + 4 * e.r_max + 0.5 * b.shear_displacement;
  const double low_h = zs - g / 2, up_lo = zs + g / 2, up_h = upper_top - up_lo;
  const Vec3 ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};
  b.first_wall = static_cast<int>(scene.walls.size());
  auto& w = scene.walls;
  w.push_back(rectangle_wall("floor", insert, {L / 2, W / 2, 0}, ez, ex, L / 2, W / 2));
  w.push_back(rectangle_wall("lower_x0", m, {0, W / 2, low_h / 2}, ex, ey, W / 2, low_h / 2));
  w.push_back(rectangle_wall("lower_x1", m, {L, W / 2, low_h / 2}, {-1, 0, 0}, ey, W / 2, low_h / 2));
  w.push_back(rectangle_wall("lower_y0", m, {L / 2, 0, low_h / 2}, ey, ex, L / 2, low_h / 2));
  w.push_back(rectangle_wall("lower_y1", m, {L / 2, W, low_h / 2}, {0, -1, 0}, ex, L / 2, low_h / 2));
  // Real halves are frames with thick walls: once the lower half has moved
  // by dx, the top face of its x0 wall closes the opening x in [0, dx] under
  // the upper half, and the bottom face of the upper half's x1 wall closes
  // x in [L, L + dx] over the lower half. Plates as wide as the travel.
  const double frame = b.shear_displacement + 2 * e.r_max;
  w.push_back(rectangle_wall("lower_frame", m, {-frame / 2, W / 2, zs - g / 2}, ez, ex, frame / 2,
                        W / 2));
  const double zu = up_lo + up_h / 2;
  w.push_back(rectangle_wall("upper_x0", m, {0, W / 2, zu}, ex, ey, W / 2, up_h / 2));
  w.push_back(rectangle_wall("upper_x1", m, {L, W / 2, zu}, {-1, 0, 0}, ey, W / 2, up_h / 2));
  w.push_back(rectangle_wall("upper_y0", m, {L / 2, 0, zu}, ey, ex, L / 2, up_h / 2));
  w.push_back(rectangle_wall("upper_y1", m, {L / 2, W, zu}, {0, -1, 0}, ex, L / 2, up_h / 2));
  w.push_back(rectangle_wall("upper_frame", m, {L + frame / 2, W / 2, zs + g / 2}, {0, 0, -1}, ex,
                        frame / 2, W / 2));
  Wall platen = rectangle_wall("platen", insert, {L / 2, W / 2, platen_z}, {0, 0, -1}, ex, L / 2, W / 2);
  // Switched on by the loading program (shear_programme.h); its settings are set
  // there too, from the specimen's stiffness.
  platen.servo.enabled = true;
  platen.servo.target_force = b.normal_stress * shear_area(b);
  platen.servo.gain = 1;
  platen.servo.max_speed = b.servo_max_speed;
  platen.tilts = b.cap == ShearBox::Cap::Tilting;  // free while a dead weight (walls.cl)
  w.push_back(platen);
}

void build(Scene& scene) {
  ShearBox& b = *scene.apparatus_as<ShearBox>();
  check_box(b, scene);
  if (auto issue = place_specimen(scene, b.specimen, b.length, b.width, "shear_box"))
    throw TableProblem{*issue};
  const SpecimenExtent e = measure_cell_specimen(scene, b.length, b.width, kCheck, "box");
  if (b.gap == 0) b.gap = 0.2 * 2 * e.r_min;
  kCheck.require(b.gap < 2 * e.r_min, "gap", b.gap,
                 "[0, " + num(2 * e.r_min) + ") m (narrower than the smallest grain)");
  if (b.split_height == 0) b.split_height = default_split_height(scene, b, e);
  kCheck.require(b.split_height > b.gap && b.split_height < e.top, "split_height", b.split_height,
          "(" + num(b.gap) + ", " + num(e.top) + ") m (inside the specimen)");
  if (!resolve_wall_material(scene, b.wall_material))
    kCheck.fail("unknown_material", "wall_material", "the box material does not exist");
  if (b.insert_material < 0) b.insert_material = b.wall_material;
  add_walls(scene, b, e);
}

}  // namespace

std::optional<SceneIssue> build_shear_box(Scene& scene) {
  if (!scene.apparatus_as<ShearBox>()) return std::nullopt;
  try {
    build(scene);
  } catch (const TableProblem& p) {
    return p.issue;
  }
  return std::nullopt;
}

std::optional<SceneIssue> check_shear_box_specimen_top(const Scene& scene, double top) {
  const ShearBox& box = *scene.apparatus_as<ShearBox>();
  if (box.split_height < top) return std::nullopt;
  return SceneIssue{"out_of_range", "shear_box.split_height",
                    "the shear plane at " + shortest_number(1e3 * box.split_height) +
                        " mm is above the prepared specimen's top at " + shortest_number(1e3 * top) +
                        " mm: set split_height inside (0, " + shortest_number(top) + ") m"};
}

double shear_area(const ShearBox& box) { return box.length * box.width; }

double shear_area_corrected(const ShearBox& box, double dx) {
  return std::max(0.0, box.length - std::fabs(dx)) * box.width;
}

LayerGrid layer_grid(const ShearBox& box, double d) { return layer_grid(box.length, box.width, d); }

int beads_per_layer(const ShearBox& box, double d) {
  return beads_per_layer(box.length, box.width, d);
}

double inertial_number_of(double speed, double height, double d, double density, double sigma) {
  return speed / height * d * std::sqrt(density / sigma);
}

double speed_for_inertial_number(double inertial_number, double height, double d, double density,
                                 double sigma) {
  return inertial_number * (height / d) * std::sqrt(sigma / density);
}

void resize_shear_box(Scene& scene, double across, double height) {
  resize_cell(scene, across, height);
  ShearBox& box = *scene.apparatus_as<ShearBox>();
  box.shear_displacement *= across;
  box.split_height *= height;
}


double shear_box_profile_stress(const Scene& s) {
  return s.apparatus_as<ShearBox>()->normal_stress;
}

void set_shear_box_inertial_number(Scene& s, double inertial_number) {
  ShearBox& b = *s.apparatus_as<ShearBox>();
  if (b.shear_speed == 0) b.inertial_number = inertial_number;
}

double shear_box_expected_time(const Scene& s) {
  const ShearBox& b = *s.apparatus_as<ShearBox>();
  const double d = 2 * s.particles.at(0).radius;
  const double rho = s.materials[s.particles[0].material].density;
  const double height = 0.8 * d * std::max(1, b.specimen.layers);
  const double v = b.shear_speed > 0 ? b.shear_speed
                                     : speed_for_inertial_number(b.inertial_number, height, d, rho, b.normal_stress);
  return b.settle_time + 0.05 + b.shear_displacement / v;
}
}  // namespace simsols
