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
#include "solver/scene/apparatus/kinds.h"

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
  // A rigid group (walls.cl): a member names its leader (a wall index,
  // -1 = none) and moves with it, its force counted in the leader's along
  // the leader's normal; a dead weight's travel along its normal from the
  // scene's position stops at `stop` (m, > 0; 0 = no stop).
  int leader = -1;
  double stop = 0;
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
  // A rectangle free to tilt: while its servo is a dead weight, it also
  // turns about axis_v through its centre as a rigid plate (moment of
  // inertia M (2 half_u)^2 / 12) under the beads' moment; otherwise it is
  // held at the tilt it has (walls.cl, HAS_TILT). Its normal and axis_u
  // above are those at zero tilt.
  bool tilts = false;
};

// Wall geometry on the host, with the wall's reference point at `point`
// (its current position, or Wall::point): the closest point of the wall to
// x, and the distance from x to the wall. Planes are one-sided, as in the
// solver: the distance to a plane is signed, negative behind it (such a
// bead is ignored); a rectangle is a two-sided plate (distance >= 0).
Vec3 wall_closest_point(const Wall& w, const Vec3& point, const Vec3& x);
// Wall w as it stands at `tilt` rad about its axis_v (Wall::tilts): its
// normal and axis_u turned as the kernels turn them (walls.cl, tilt_axes).
Wall tilted_wall(const Wall& w, double tilt);
double wall_distance(const Wall& w, const Vec3& point, const Vec3& x);

// The contact and body-force model as named slots, each with a `none`
// choice (docs/model.md, "Effects as slots"). Every slot becomes a kernel
// build option (cl_program.h): a slot set to none leaves no code and no
// per-contact memory in the kernels. The normal law (Hertz) is always on.
enum class DampingModel : std::uint8_t { None, Viscous };
enum class TangentialModel : std::uint8_t { None, Mindlin, MindlinDeresiewicz };
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
                                                       // (mindlin_deresiewicz: micro-slip)
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

// A periodic cell (solver/core/periodic_box.h, docs/periodic-cell.md): the
// scene's space repeats along the cell's edges, the columns of `edges`
// (row-major, upper triangular), from `corner`. The periodic_cell
// apparatus sets it; a scene with one has no walls, no gravity, no clumps
// and runs in double precision.
struct PeriodicBox {
  std::array<double, 9> edges{};  // m
  Vec3 corner{};                  // m
  double preparation_friction = 0;  // mu_s while the specimen is made (compiled in when > 0)
  double preparation_restitution = 1;  // restitution while it is made (damping compiled in when < 1)
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

// A flexible membrane of bonded beads (kernels/membrane.cl): the particles
// [first, first + rows * cols), row by row, each row a closed ring of
// `cols` beads about the z axis, counter-clockwise seen from above. Beads
// of one membrane never touch each other; each is tied to its four lattice
// neighbours by springs that pull but do not push (a membrane folds rather
// than carrying compression), and an interior bead carries the cell
// pressure on its share of the surface. The first and last rows are sealed
// to the floor and to the platen wall (held, the last moving with the
// platen). The pressure, the bonds' rest lengths and whether the whole
// membrane is held are state (Simulation::set_membrane); an apparatus
// builds the record (triaxial.h, cell = "membrane").
struct Membrane {
  int first = -1;  // first bead; -1: the scene has no membrane
  int rows = 0, cols = 0;
  int platen_wall = -1;  // the wall the last row moves with; -1: held still
  double stiffness = 0;  // N/m, the membrane's E t (both directions)
  double damping = 0.5;  // the bonds' dashpots, fraction of critical
  int count() const { return first >= 0 ? rows * cols : 0; }
};

// The specimen and the apparatus cell every apparatus shares (specimen.h),
// the kinds' descriptions and the Apparatus variant (apparatus/kinds.h).

struct Scene {
  std::string name = "unnamed";
  std::string description;
  std::vector<Material> materials;
  std::vector<PairOverride> pair_overrides;
  std::vector<Particle> particles;
  std::vector<Grain> grains;
  std::vector<Clump> clumps;  // rigid bodies of member particles
  std::vector<Wall> walls;
  std::optional<PeriodicBox> periodic;
  Membrane membrane;  // built by an apparatus (triaxial cell = "membrane")
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
  // registry but the periodic cell adds walls, one of them servo-controlled, and a
  // specimen of clumps when its specimen pours a grain; a periodic cell's
  // reader sets `periodic` at once (make_kernel_config counts on both).
  std::vector<Generator> generators;
  bool apparatus_pending = false;
  bool placed() const { return generators.empty() && !apparatus_pending; }

  // Where it came from (empty for scenes built in code).
  std::string source_path;
  std::string source_text;

  int material_index(const std::string& name) const;  // -1 when absent
  double mass(const Particle& p) const;  // kg, a solid sphere of its material
  double total_mass() const;             // kg, of every particle
  // The particles that are not a membrane's beads, which an apparatus appends last.
  size_t specimen_count() const {
    return membrane.count() > 0 ? size_t(membrane.first) : particles.size();
  }
  bool has_gravity() const;
  // The apparatus when it is an A (one of apparatus/kinds.h), else nullptr.
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
