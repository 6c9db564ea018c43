// Scene: the static, read-only description of one experiment.
//
// A Scene is what MuJoCo calls the model (mjModel): materials, particles,
// walls, the effects switched on, numerics and outputs. It never changes
// while a simulation runs; everything that evolves lives in State (device
// buffers, see state.h). A Scene is plain data in SI units (metres, seconds,
// kilograms, pascals), built either in code (tests) or read from a TOML file
// by read_scene() and placed by place_scene() (scene_toml.h).
// validate_scene() checks the semantic rules shared by both paths;
// contact_model.h derives the per-pair coefficients and the stable time
// step from it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "solver/common/vec3.h"

namespace simsols {


// One bulk material. Units: Pa, -, kg/m^3, -, -, m.
struct Material {
  std::string name;
  double young_modulus = 0;      // E, Pa, > 0
  double poisson_ratio = 0;      // nu, in [0, 0.5)
  double density = 0;            // rho, kg/m^3, > 0
  double restitution = 1;        // normal coefficient of restitution, [kMinRestitution = 0.01, 1]
  double sliding_friction = 0;   // mu_s, >= 0
  double rolling_friction = 0;   // mu_r, metres (a lever arm), >= 0
};

// Optional override of the pair properties between two materials. When no
// override exists, a pair uses the mean restitution, the smaller sliding
// friction and the smaller rolling friction of its two materials.
struct PairOverride {
  int material_a = 0;
  int material_b = 0;
  std::optional<double> restitution;
  std::optional<double> sliding_friction;
  std::optional<double> rolling_friction;
  std::optional<double> liquid_volume;  // capillary cohesion, m^3
  std::optional<double> contact_angle;  // capillary cohesion, rad
};

// The glass beads of the reference paper, its Table 2: E = 62.784 GPa,
// nu = 0.2, rho = 2230 kg/m^3, e = 0.87, mu_s = 0.02, mu_r = 5e-5 m.
inline Material paper_glass() {
  return {"glass", 62.784e9, 0.2, 2230, 0.87, 0.02, 5e-5};
}

struct Particle {
  int material = 0;   // index into Scene::materials
  double radius = 0;  // m
  Vec3 position{};    // m
  Vec3 velocity{};    // m/s
  Vec3 angular_velocity{};  // rad/s
  int clump = -1;     // the clump it belongs to (Scene::clumps), -1 for a free sphere
};

// A [[generators]] entry as read (docs/scene-format.md): spheres on a
// lattice or at random without overlap, not yet placed. place_scene
// (solver/io/scene_toml.h) expands it (generators.h), deterministic on
// every platform.
struct Generator {
  enum class Type : std::uint8_t { Lattice, Random };
  Type type = Type::Lattice;
  int material = 0;
  Vec3 min{}, max{};      // m, the box the spheres lie in
  Vec3 velocity{};        // m/s, of every sphere
  std::uint64_t seed = 1;
  double radius_min = 0;  // m; a lattice's spheres, and an equal-size random fill, have
  double radius_max = 0;  //    radius_min = radius_max
  double spacing = 0;     // Lattice: m between nearest neighbours
  bool hexagonal = false; // Lattice: FCC close-packed layers instead of cubic
  double jitter = 0;      // Lattice: m, each coordinate moved by up to this
  std::int64_t count = 0; // Random: how many; Lattice: at most this many, 0 = every site
};

// A grain shape made of overlapping spheres, in its own frame (a clump
// template: docs/specimens.md).
struct Grain {
  std::string name;
  std::vector<std::array<double, 4>> spheres;  // x, y, z, radius (m)
  std::string origin;  // how a template made the spheres (grain_templates.h); empty when listed
};

// A rigid clump of a grain's spheres. Its member spheres are particles
// [first, first + count) of the scene, placed at read time from the
// grain's spheres scaled by `scale` and turned by `orientation` (a unit
// quaternion w, x, y, z, the grain's frame to the scene's) about the
// union's centroid, which sits at `position`.
struct Clump {
  int grain = 0;      // index into Scene::grains
  double scale = 1;   // the grain's size times this (a graded pour's drawn size)
  int material = 0;
  Vec3 position{};    // m, the union's centroid
  std::array<double, 4> orientation{1, 0, 0, 0};
  Vec3 velocity{};          // m/s, of the centroid
  Vec3 angular_velocity{};  // rad/s
  int first = 0, count = 0;  // its member particles
};

enum class WallShape : std::uint8_t { Plane, Rectangle };

// Force control of a wall: it moves along its normal so that the force the
// particles exert on it, F = -(force on the wall) . normal, tends to
// target_force, in one of two ways.
//   servo (mass = 0): a proportional-integral law on e = target_force - F,
//     v = clamp(gain e + v_i, -max_speed, max_speed) normal,
//     dv_i/dt = gain e / integral_time   (off when integral_time = 0);
//   dead weight (mass > 0): the wall is a rigid body of that mass pushed
//     along its normal by the constant force target_force (a hanger's
//     weight), so M du/dt = target_force - F; gain, max_speed and
//     integral_time are unused.
// A force-controlled wall has no prescribed velocity.
struct WallServo {
  bool enabled = false;
  double target_force = 0;   // N, > 0
  double gain = 0;           // m/(s N), > 0 (servo)
  double max_speed = 0;      // m/s, > 0 (servo)
  double integral_time = 0;  // s, >= 0; 0 = proportional only (servo)
  double mass = 0;           // kg, >= 0; > 0 = dead weight
};

// A rigid wall moving with a prescribed constant velocity, or servo-controlled.
// Plane: infinite, one-sided; particles live on the side `normal` points to.
// Rectangle: finite, two-sided thin plate centred at `point`, spanned by
//   axis_u (unit) and axis_v = normal x axis_u, half sizes half_u, half_v.
struct Wall {
  std::string name;
  WallShape shape = WallShape::Plane;
  int material = 0;
  Vec3 point{};        // a point on the plane / the rectangle centre, m
  Vec3 normal{0, 0, 1};  // unit normal
  Vec3 axis_u{1, 0, 0};  // rectangle only: unit in-plane axis, normal to `normal`
  double half_u = 0;   // rectangle only, m
  double half_v = 0;   // rectangle only, m
  Vec3 velocity{};     // m/s, prescribed
  WallServo servo;     // when enabled, moves to hold a normal force instead
};

// Wall geometry on the host, with the wall's reference point at `point`
// (its current position, or Wall::point): the closest point of the wall to
// x, and the distance from x to the wall. Planes are one-sided, as in the
// solver: the distance to a plane is signed, negative behind it (such a
// bead is ignored); a rectangle is a two-sided plate (distance >= 0).
Vec3 wall_closest_point(const Wall& w, const Vec3& point, const Vec3& x);
double wall_distance(const Wall& w, const Vec3& point, const Vec3& x);

// The contact and body-force model as named slots, each with a `none`
// choice (docs/model.md, "Effects as slots"). Every slot becomes a kernel
// build option (cl_program.h): a slot set to none leaves no code and no
// per-contact memory in the kernels. The normal law (Hertz) is always on.
enum class DampingModel : std::uint8_t { None, Viscous };
enum class TangentialModel : std::uint8_t { None, Mindlin };
enum class RollingModel : std::uint8_t { None, ConstantTorque, SpringDashpot };
enum class CohesionModel : std::uint8_t { None, Capillary };
enum class FluidModel : std::uint8_t { None, Drag };

// Capillary liquid bridge between two beads (Rabinovich et al. 2005 force,
// Lian et al. 1993 rupture distance; docs/model.md). Per material pair:
// [[interactions]] may override liquid_volume and contact_angle.
struct Capillary {
  double surface_tension = 0.072;  // gamma, N/m, > 0 (water at 25 C)
  double contact_angle = 0;        // theta, rad, [0, pi/2)
  double liquid_volume = 0;        // V per bridge, m^3, > 0
};

// A still or uniformly moving Newtonian fluid around the beads: drag force
// (Schiller-Naumann), drag moment and buoyancy (docs/model.md).
struct Fluid {
  double density = 1000;     // rho_f, kg/m^3, >= 0
  double viscosity = 1e-3;   // mu_f, Pa s, > 0
  Vec3 velocity{};           // u, m/s, uniform
};

struct Effects {
  Vec3 gravity{0, 0, -9.81};     // m/s^2; all zero switches gravity off
  DampingModel damping = DampingModel::Viscous;          // normal + tangential dashpots
  TangentialModel tangential = TangentialModel::Mindlin; // spring with history + Coulomb
  RollingModel rolling = RollingModel::ConstantTorque;
  double rolling_damping = 0.3;  // spring_dashpot: eta_r, fraction of critical, [0, 1]
  CohesionModel cohesion = CohesionModel::None;
  Capillary capillary;           // when cohesion = Capillary
  FluidModel fluid = FluidModel::None;
  Fluid fluid_params;            // when fluid = Drag
};

// The names of the slots' choices ("viscous", "none", ...): choices.h.

// Lian et al. (1993) rupture distance of a liquid bridge, m.
double capillary_rupture_distance(double liquid_volume, double contact_angle);

enum class Precision : std::uint8_t { Float, Double };

struct Numerics {
  Precision precision = Precision::Double;
  double dt = 0;               // s; 0 = automatic (dt_fraction x Rayleigh step)
  double dt_fraction = 0.15;   // of the Rayleigh time step, in (0, max_dt_fraction]
  bool force_dt = false;       // accept a dt above the stability limit
  double duration = 0;         // simulated time, s, > 0
  double skin = 0;             // neighbour-list skin, m; 0 = 0.1 x largest diameter
  int neighbor_capacity = 0;   // neighbours per particle; 0 = automatic
};

// Walls per scene (each particle keeps a bitmask of the walls it touches).
inline constexpr size_t kMaxWalls = 32;

// Limit on dt: a requested step larger than this fraction of the Rayleigh
// step is refused unless Numerics::force_dt is set.
inline constexpr double kMaxDtFraction = 0.5;

// Optional [view]: how frames of this scene are drawn by default (`simsols
// snapshot`, `run --frames`, the lab); command-line flags override. Kept as
// given; the app checks the values (allowed ones in docs/rendering.md) and
// reports a bad one with the file and field.
struct ViewHints {
  std::string view;      // camera preset; empty = default
  std::string color_by;  // bead colour field
  std::string mode;      // opaque, transparent, chains
  std::string size;      // WxH
  std::optional<bool> chains;
  std::optional<double> threshold;
  bool empty() const {
    return view.empty() && color_by.empty() && mode.empty() && size.empty() && !chains &&
           !threshold;
  }
};

struct Outputs {
  double series_interval = 0;      // s between time-series rows; 0 = duration/1000
  double dump_interval = 0;        // s between particle dumps; 0 = only the last state
  double checkpoint_interval = 0;  // s between checkpoints; 0 = only at the end
  bool dump_csv = true;
  bool dump_vtk = true;
};

// The specimen of an apparatus with a rectangular cell: how its beads are
// placed (apparatus/specimen.h).
// A grading curve: the mass fraction of a specimen passing each size, as a
// sieve analysis gives it (docs/specimens.md; solver/apparatus/specimen/grading.h).
struct Grading {
  enum class Law : std::uint8_t { Single, Uniform, LogNormal, Fuller, Sieve };
  Law law = Law::Single;       // Single: every bead of specimen.diameter
  double d_min = 0, d_max = 0; // m, the cut-offs (0 = the law's default where it has one)
  double sigma = 0.25;         // LogNormal: standard deviation of ln d, by mass (D50 = diameter)
  double exponent = 0.5;       // Fuller: P = (d^n - d_min^n) / (d_max^n - d_min^n)
  std::vector<double> sizes;   // Sieve: m, increasing
  std::vector<double> passing; // Sieve: % by mass, from 0 to 100, non-decreasing
};

// How a specimen is brought to its density (docs/specimens.md). The
// friction applies while the specimen settles (lubricated or rough
// preparation), then the materials' own friction takes over; the pour's
// drop height and intensity shape its rain.
struct Preparation {
  std::optional<double> friction;          // mu_s of every pair while settling; unset: the materials'
  std::optional<double> rolling_friction;  // mu_r (m) while settling; unset: the materials'
  double drop_height = 0;  // m, Pour: the beads start at the speed of a free fall from this height
  double intensity = 0;    // Pour: solid fraction of the raining column, (0, 0.35]; 0: 3 specimen heights tall
  std::optional<double> relative_density;  // target D_r: the friction is searched (docs/specimens.md)
  std::optional<double> e_min, e_max;      // the material's index void ratios, when known
  int tamping_layers = 0;                  // Pour: built in this many tamped layers (0: poured at once)
  std::optional<double> void_ratio;        // target e of tamping or expansion (or from relative_density)
  double undercompaction = 0.05;           // Ladd's U_1: the bottom layer's shortfall of dry density
  bool expansion = false;                  // Pour of spheres: grown in the closed cell (radius expansion)
  bool settles_differently() const { return friction || rolling_friction; }
};

struct Specimen {
  enum class Method : std::uint8_t { Layers, Pour, Given };
  enum class Clearance : std::uint8_t { Shift, Spread };
  Method method = Method::Layers;  // Table 1 layers / random pour / the scene's particles
  int material = 0;                // the beads' material
  double diameter = 0;             // m (Layers, Pour)
  int layers = 0;                  // Layers: layers; Pour: beads for that many layers
  Clearance clearance = Clearance::Shift;  // Layers: how the row-wall clearance is used
  std::int64_t seed = 1;
  Grading grading;                 // Pour: the sizes' distribution
  int grain = -1;                  // Pour: clumps of this grain (Scene::grains) instead of beads
  Preparation preparation;         // how it settles (every method)
};

// What every apparatus is: a cell on a floor at z = 0, x in [0, length],
// y in [0, width], holding a specimen, its walls Scene::walls[first_wall..]
// (in the apparatus' own order). The builders (the registry's `build`,
// solver/apparatus/registry.h) place the specimen and add the walls.
struct ApparatusCell {
  double length = 0;           // m, inside, along x
  double width = 0;            // m, inside, along y
  int wall_material = -1;      // the walls' material; -1 = "steel" (added when absent)
  double settle_time = 0.01;   // s, longest settling under gravity
  Specimen specimen;
  int first_wall = 0;          // set by the builder
};


// The direct shear apparatus of the reference paper (its section 5) and its
// loading program. The box is x in [0, length] (the shear direction),
// y in [0, width], floor at z = 0, split at z = split_height into a lower and
// an upper half with `gap` between them. The lower half (floor and four side
// plates) moves in +x at the shear speed; the upper half and the platen are
// held horizontally; the platen is servo-controlled to the normal stress.
// build_shear_box() (shear_box.h) turns this into twelve walls (and particles) and
// resolves the automatic values (0 below) into numbers.
struct ShearBox : ApparatusCell {
  ShearBox() { length = 60.23e-3; width = 60.07e-3; }  // inside: x the shear direction
  double split_height = 0;         // m; 0 = mid-height of the specimen (see shear_box.h)
  double gap = 0;                  // m between the halves; 0 = 0.2 x smallest diameter
  double normal_stress = 160e3;    // Pa, the platen's target
  double shear_speed = 0;          // m/s; 0 = from inertial_number
  double inertial_number = 8e-4;   // target I = (v/H) d sqrt(rho/sigma) for the automatic speed
  double shear_displacement = 6e-3;  // m of horizontal displacement to shear
  // How the platen carries the normal load (docs/shear-box.md): a dead
  // weight (a rigid platen of platen_mass under the constant force
  // sigma x area, as a hanger loads a real box) or a servo (PI on the
  // reaction, servo_* below). Consolidation is servo-controlled in both.
  enum class Loading : std::uint8_t { DeadWeight, Servo };
  Loading loading = Loading::DeadWeight;
  double platen_mass = 0;          // kg; 0 = automatic (a quarter layer of beads, pi rho d A / 24)
  double servo_gain = 0;           // m/(s N); 0 = automatic (from the Hertz stiffness)
  double servo_max_speed = 0.5;    // m/s, the platen's speed cap
  double servo_integral_time = 0;  // s; 0 = automatic
  double consolidate_time = 0.1;   // s, longest consolidation under the platen
  int rows = 400;                  // output rows over the shear displacement
};

// The apparatus walls, in this order from ShearBox::first_wall: the lower
// half [kFloor, kLowerLast], the upper half and platen [kUpperX0, kPlaten].
// The frames are the top face of the lower half's x0 wall and the bottom
// face of the upper half's x1 wall (see shear_box.h).
enum ShearBoxWall : int {
  kFloor = 0, kLowerX0, kLowerX1, kLowerY0, kLowerY1, kLowerFrame,
  kUpperX0, kUpperX1, kUpperY0, kUpperY1, kUpperFrame, kPlaten, kShearBoxWalls,
  kLowerLast = kLowerFrame
};

// The oedometer (one-dimensional compression, docs/oedometer.md): a rigid
// square ring x in [0, length], y in [0, width] on a floor at z = 0, and a
// top platen servo-controlled to each vertical stress of `load_steps` in
// turn, each held until the specimen is in equilibrium under it (or for
// step_time at most). The steps up to the largest are the loading branch,
// those after it the unloading branch. build_oedometer() (apparatus/
// oedometer.h) turns this into six walls (and particles) and resolves the
// automatic values (0 below).
struct Oedometer : ApparatusCell {
  Oedometer() { length = 60e-3; width = 60e-3; }  // inside
  std::vector<double> load_steps = {25e3, 50e3, 100e3, 200e3, 400e3, 800e3, 200e3, 50e3, 25e3};  // Pa
  double step_time = 0.1;          // s, longest hold of one load step
  double servo_gain = 0;           // m/(s N); 0 = automatic (from the Hertz stiffness)
  double servo_max_speed = 0.5;    // m/s, the platen's speed cap
  double servo_integral_time = 0;  // s; 0 = automatic
  double friction_angle = 0;       // deg, phi' for Jaky's K0 = 1 - sin phi'; 0 = none given
};

// The oedometer's walls, in this order from Oedometer::first_wall.
enum OedometerWall : int {
  kOedFloor = 0, kOedX0, kOedX1, kOedY0, kOedY1, kOedPlaten, kOedometerWalls
};

// The triaxial test (docs/triaxial.md): a cuboid specimen between six
// rigid plates, x in [0, length], y in [0, width] on a floor at z = 0. The
// floor is fixed; the top platen and the four sides are servo-controlled.
// Stages: isotropic consolidation to confining_stress on all five, then
// drained axial compression, the platen moved down at a constant strain
// rate while the sides hold the lateral stresses of the stress path:
//   constant_sigma3  both lateral stresses at confining_stress (the
//                    conventional test);
//   constant_p       the lateral stresses follow sigma3 = (3 p0 - sigma1)/2
//                    so the mean stress p' stays at confining_stress (never
//                    below 5 % of it: the sides keep the specimen closed);
//   true_triaxial    sigma3 (x) at confining_stress, sigma2 (y) at
//                    sigma3 + b (sigma1 - sigma3).
// build_triaxial() (apparatus/triaxial.h) turns this into six walls (and
// particles) and resolves the automatic values (0 below).
struct Triaxial : ApparatusCell {
  Triaxial() { length = 30e-3; width = 30e-3; settle_time = 0.02; }  // inside at the start
  enum class Path : std::uint8_t { ConstantSigma3, ConstantP, TrueTriaxial };
  double confining_stress = 100e3; // Pa, p'0 and sigma3
  Path path = Path::ConstantSigma3;
  double b_value = 0.5;            // true_triaxial: (sigma2 - sigma3) / (sigma1 - sigma3), [0, 1]
  double axial_strain = 0.15;      // to compress to
  double strain_rate = 0;          // 1/s; 0 = from inertial_number
  double inertial_number = 5e-4;   // target I = strain_rate d sqrt(rho / p0)
  double consolidate_time = 0.1;   // s, longest isotropic consolidation
  double servo_gain = 0;           // m/(s N); 0 = automatic (from the Hertz stiffness)
  double servo_max_speed = 0.5;    // m/s, the plates' speed cap
  double servo_integral_time = 0;  // s; 0 = automatic
  int rows = 200;                  // rows over the axial strain
};

// The triaxial cell's walls, in this order from Triaxial::first_wall.
enum TriaxialWall : int {
  kTriFloor = 0, kTriX0, kTriX1, kTriY0, kTriY1, kTriPlaten, kTriaxialWalls
};

// A scene's apparatus: none, or one of the kinds in the registry's order
// (solver/apparatus/registry.h: a new kind is added there and here).
using Apparatus = std::variant<std::monostate, ShearBox, Oedometer, Triaxial>;

struct Scene {
  std::string name = "unnamed";
  std::string description;
  std::vector<Material> materials;
  std::vector<PairOverride> pair_overrides;
  std::vector<Particle> particles;
  std::vector<Grain> grains;
  std::vector<Clump> clumps;  // rigid bodies of member particles
  std::vector<Wall> walls;
  Effects effects;
  Numerics numerics;
  Outputs outputs;
  ViewHints view;
  // The scene's apparatus, at most one (its walls are included in `walls`).
  // What each kind is and does is told by the registry
  // (solver/apparatus/registry.h), not by the code that holds a scene.
  Apparatus apparatus;

  // What reading a file leaves to place_scene (solver/io/scene_toml.h):
  // the generators still to expand, and the apparatus whose walls and
  // specimen are still to build. A scene built in code, or placed, has
  // neither; a Simulation takes only a placed scene. Every apparatus of the
  // registry adds walls, one of them servo-controlled, and a specimen of
  // clumps when its specimen pours a grain (make_kernel_config counts on it).
  std::vector<Generator> generators;
  bool apparatus_pending = false;
  bool placed() const { return generators.empty() && !apparatus_pending; }

  // Where it came from (empty for scenes built in code).
  std::string source_path;
  std::string source_text;

  int material_index(const std::string& name) const;  // -1 when absent
  double mass(const Particle& p) const;  // kg, a solid sphere of its material
  double total_mass() const;             // kg, of every particle
  bool has_gravity() const;
  // The apparatus when it is an A (ShearBox, Oedometer, Triaxial), else nullptr.
  template <class A>
  const A* apparatus_as() const { return std::get_if<A>(&apparatus); }
  template <class A>
  A* apparatus_as() { return std::get_if<A>(&apparatus); }
  bool has_apparatus() const { return apparatus.index() != 0; }
  // The cell every apparatus has (ApparatusCell); nullptr without one.
  const ApparatusCell* cell() const;
  ApparatusCell* cell();
  // The specimen of the scene's apparatus; nullptr without one.
  const Specimen* specimen() const;
  Specimen* specimen();
  // Largest capillary rupture distance of any pair (0 without cohesion), m.
  double rupture_distance() const;
};

}  // namespace simsols
