// Simulation: a Model and its State on one device, the unit tests and the
// app drive. Thin by design: the physics is in the pipeline stages, the
// measuring in observe.h, persistence in checkpoint.h.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/core/guard.h"
#include "solver/core/model.h"
#include "solver/core/observe.h"
#include "solver/core/pipeline.h"
#include "solver/core/state.h"

namespace simsols {

class Simulation {
 public:
  Simulation(std::shared_ptr<Device> device, const Scene& scene);

  const Model& model() const { return *model_; }
  State& state() { return *state_; }
  const Scene& scene() const { return model_->scene(); }

  // Throws RunawayError when a step goes wrong; the simulation is then at
  // the last good state, the step before (guard.h).
  void advance(std::int64_t steps = 1);
  double time() const { return state_->time; }
  std::int64_t steps() const { return state_->step; }
  double dt() const { return model_->dt(); }

  // Run-time control of the walls (the loading program): a prescribed
  // velocity, and a servo's settings (switching it on or off, retargeting).
  void set_wall_velocity(int wall, const Vec3& velocity);
  void set_servo(int wall, const WallServo& servo);
  // What the servo of `wall` measured: the reaction of the last step and its
  // mean over the steps since the previous call (which restarts the mean).
  struct ServoReading {
    double last = 0, mean = 0;
    std::int64_t steps = 0;
  };
  ServoReading read_servo(int wall);
  // The wall's servo as it is set now (by the scene, or set_servo since):
  // its target force, gain, speed cap, integral time, the dead weight's
  // mass; not enabled when the kernels have no servo walls.
  WallServo servo_setting(int wall);
  Vec3 wall_point(int wall);  // current reference point, absolute
  Vec3 wall_velocity(int wall);  // m/s, prescribed or set by its force control
  // A wall that may tilt (Wall::tilts): its tilt about its axis_v (rad,
  // right-handed), its rate (rad/s) and the beads' moment on it last step
  // (N m, counted only while it is free to turn); zeros for other walls.
  struct Tilt {
    double angle = 0, rate = 0, moment = 0;
  };
  Tilt wall_tilt(int wall);
  // Moves a wall at once (no sweep: the caller makes sure it lands clear of
  // the particles, e.g. a platen lowered onto a specimen).
  void set_wall_point(int wall, const Vec3& point);
  // A periodic cell's velocity gradient L (upper triangular) from the next
  // step on (periodic_box.h); the cell as it stands is state().cell_now.
  // Throws std::invalid_argument for a gradient that is not upper
  // triangular, std::logic_error without a periodic cell.
  void set_cell_gradient(const Mat3& grad);
  // Settles a specimen with other friction than its materials' (a
  // preparation, scene.h); std::nullopt restores the materials' (model.h).
  void override_friction(const std::optional<Model::FrictionOverride>& friction) {
    model_->override_friction(friction);
  }
  // The membrane's setting (scene.h, Membrane; membrane.cl): the cell
  // pressure (Pa, inwards), whether every bead is held, each direction's
  // bond rest length (m) and stiffness (N/m), and its axis; the dashpots
  // follow from Membrane::damping. Throws std::logic_error without one.
  struct MembraneSetting {
    double pressure = 0;
    bool held = true;
    double rest_hoop = 0, rest_axial = 0;  // m
    double k_hoop = 0, k_axial = 0;        // N/m
    double axis_x = 0, axis_y = 0;         // m: the vertical line it is wrapped about
  };
  void set_membrane(const MembraneSetting& setting);
  MembraneSetting membrane_setting();
  // Puts particles first, first + 1, ... at `positions` (absolute), at rest,
  // and rebuilds the lists before the next step (a membrane wrapped about a
  // specimen). Throws std::out_of_range past the last particle.
  void place_particles(size_t first, const std::vector<Vec3>& positions);
  // Moves the particle in state slot `slot` by dx at once (the accuracy
  // study's round-off twin at the start of shearing).
  void nudge_particle(size_t slot, const Vec3& dx);
  // Scales every particle's radius by `factor` (and its mass by factor^3)
  // where it is, and rebuilds the lists: radius expansion
  // (solver/apparatus/specimen/expansion.h). Spheres only; the scene's radii (and
  // the grid's cells, sized from them) are not changed: grow no bead past
  // the radius its cell was sized for (Numerics::skin leaves the room).
  void scale_radii(double factor);
  // Mean force the particles exerted on each wall over the steps since the
  // previous call (which restarts the means); needs a servo wall in the
  // scene (the servo stage keeps the sums). Empty when there is none.
  struct WallMean {
    Vec3 force{};
    std::int64_t steps = 0;
  };
  std::vector<WallMean> read_wall_means();

  // Readings first make sure no step since the guard's last look went wrong
  // (they throw RunawayError otherwise), so no output holds a bad value.
  Observables observe() {
    guard_->before_reading();
    return simsols::observe(*model_, *state_);
  }
  std::vector<WallReaction> wall_reactions() {
    guard_->before_reading();
    return simsols::wall_reactions(*model_, *state_);
  }
  ParticleSnapshot snapshot() {
    guard_->before_reading();
    return download(*model_, *state_);
  }
  std::vector<ClumpState> clumps() {
    guard_->before_reading();
    return clump_states(*model_, *state_);
  }
  std::vector<ContactForce> contacts() {
    guard_->before_reading();
    return contact_list(*model_, *state_);
  }
  // The state as it is (no guard look: also for a state being diagnosed).
  std::uint64_t hash() { return state_hash(*model_, *state_); }

  // The runaway guard (guard.h). check() reads the mark now.
  Guard& guard() { return *guard_; }
  void check() { guard_->before_reading(); }
  // After the state buffers were written wholesale (a checkpoint loaded).
  void state_replaced() { guard_->reset(); }

 private:
  void write_real4(Buffer State::*buffer, size_t index, double a, double b, double c, double d);

  std::unique_ptr<Model> model_;
  std::unique_ptr<State> state_;
  std::unique_ptr<Guard> guard_;
};

// Advances one step at a time until particle `i` has touched something and
// separated again (an impact), at most `max_steps` steps; false when the
// contact never ended. Used by impact checks (tests, the accuracy study).
bool advance_through_contact(Simulation& sim, int i, std::int64_t max_steps);


}  // namespace simsols
