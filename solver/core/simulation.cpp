#include "solver/core/simulation.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "solver/core/real_packer.h"

namespace simsols {

Simulation::Simulation(std::shared_ptr<Device> device, const Scene& scene)
    : model_(std::make_unique<Model>(std::move(device), scene)),
      state_(std::make_unique<State>(*model_)),
      guard_(std::make_unique<Guard>(*model_, *state_)) {
  guard_->reset();
}

void Simulation::advance(std::int64_t steps) {
  for (std::int64_t i = 0; i < steps; ++i) {
    step(*model_, *state_);
    guard_->after_step();
  }
}

namespace {

void check_wall(const Model& m, int wall, const char* what) {
  if (wall < 0 || wall >= m.walls())
    throw std::out_of_range(std::string(what) + ": wall " + std::to_string(wall) +
                            " does not exist (the scene has " + std::to_string(m.walls()) +
                            " walls)");
}

std::array<double, 4> read_real4(const Model& m, const Buffer& buf, size_t index) {
  const std::vector<double> v = read_reals(m, buf, 4, 4 * index);
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace

// Writes one real4 at record `index` of a state buffer, through the guard's
// log (a replay repeats it).
void Simulation::write_real4(Buffer State::*buffer, size_t index, double a, double b, double c,
                             double d) {
  RealPacker p(model_->config().double_precision);
  p.put4(a, b, c, d);
  guard_->write(buffer, index * p.size(), p.data(), p.size());
}

void Simulation::set_cell_gradient(const Mat3& grad) {
  if (!model_->config().periodic) throw std::logic_error("set_cell_gradient: the scene has no periodic cell");
  if (!upper_triangular(grad))
    throw std::invalid_argument("the periodic cell's velocity gradient must be upper triangular");
  CellNow c = state_->cell_now;
  c.grad = grad;
  const std::vector<double> rec = cell_record(*model_, c);
  guard_->write(&State::cell, 0, rec.data(), rec.size() * sizeof(double));  // then the mirror
  state_->cell_now = c;
}

void Simulation::set_wall_velocity(int wall, const Vec3& v) {
  check_wall(*model_, wall, "set_wall_velocity");
  write_real4(&State::wall_vel, wall, v[0], v[1], v[2], 0);
}

void Simulation::set_servo(int wall, const WallServo& c) {
  check_wall(*model_, wall, "set_servo");
  if (c.leader >= 0) check_wall(*model_, c.leader, "set_servo (leader)");
  if (c.leader == wall || !(c.stop >= 0))
    throw std::invalid_argument("set_servo: a wall cannot lead itself, and a stop is >= 0 m");
  if (c.enabled && !model_->config().servo)
    throw std::logic_error("set_servo: the kernels were built without servo walls");
  if (!model_->config().servo) return;
  const std::array<double, 8> r = servo_record(c);
  write_real4(&State::servo, 2 * wall, r[0], r[1], r[2], r[3]);
  write_real4(&State::servo, 2 * wall + 1, r[4], r[5], r[6], r[7]);
  if (state_->tilting) {  // free to turn while a dead weight, else held where it is
    const double inv_j = tilt_inverse_inertia(model_->scene().walls[size_t(wall)], c);
    const auto t = read_real4(*model_, state_->wall_turn, wall);
    write_real4(&State::wall_turn, wall, t[0], inv_j > 0 ? t[1] : 0, inv_j, inv_j > 0 ? t[3] : 0);
  }
  if (!c.enabled) {
    set_wall_velocity(wall, {0, 0, 0});
    const auto r = read_real4(*model_, state_->wall_reaction, wall);
    write_real4(&State::wall_reaction, wall, r[0], r[1], 0, r[3]);  // no stale integral
  }
}

WallServo Simulation::servo_setting(int wall) {
  check_wall(*model_, wall, "servo_setting");
  WallServo s;
  if (!model_->config().servo) return s;
  guard_->before_reading();
  const auto a = read_real4(*model_, state_->servo, 2 * size_t(wall));
  const auto b = read_real4(*model_, state_->servo, 2 * size_t(wall) + 1);
  s.target_force = a[0];  // the order of servo_record (state.cpp)
  s.gain = a[1];
  s.max_speed = a[2];
  s.enabled = a[3] != 0;
  s.integral_time = b[0] > 0 ? 1 / b[0] : 0;
  s.mass = b[1] > 0 ? 1 / b[1] : 0;
  s.leader = static_cast<int>(b[2]) - 1;
  s.stop = b[3];
  return s;
}

Simulation::ServoReading Simulation::read_servo(int wall) {
  check_wall(*model_, wall, "read_servo");
  guard_->before_reading();
  const auto r = read_real4(*model_, state_->wall_reaction, wall);
  write_real4(&State::wall_reaction, wall, r[0], 0, r[2], 0);
  ServoReading out;
  out.last = r[0];
  out.steps = static_cast<std::int64_t>(r[3]);
  out.mean = out.steps > 0 ? r[1] / r[3] : r[0];
  return out;
}

Vec3 Simulation::wall_point(int wall) {
  check_wall(*model_, wall, "wall_point");
  guard_->before_reading();
  return wall_points(*model_, *state_)[wall];
}

Vec3 Simulation::wall_velocity(int wall) {
  check_wall(*model_, wall, "wall_velocity");
  guard_->before_reading();
  const auto v = read_real4(*model_, state_->wall_vel, wall);
  return {v[0], v[1], v[2]};
}

Simulation::Tilt Simulation::wall_tilt(int wall) {
  check_wall(*model_, wall, "wall_tilt");
  if (!state_->tilting) return {};
  guard_->before_reading();
  const auto t = read_real4(*model_, state_->wall_turn, wall);
  return {t[0], t[1], t[3]};
}

void Simulation::nudge_particle(size_t slot, const Vec3& dx) {
  if (slot >= static_cast<size_t>(model_->particles()))
    throw std::out_of_range("nudge_particle: slot " + std::to_string(slot) + " does not exist");
  const auto p = read_real4(*model_, state_->pos, slot);
  double at[3] = {p[0] + dx[0], p[1] + dx[1], p[2] + dx[2]};
  if (!model_->config().double_precision) {
    // the float run's position is pos + pos_lo: move their sum
    float lo[4];
    model_->device().read(state_->pos_lo.get(), sizeof lo, lo, slot * sizeof lo);
    for (int a = 0; a < 3; ++a) at[a] += lo[a];
    const float fresh[4] = {float_remainder(at[0]), float_remainder(at[1]),
                            float_remainder(at[2]), lo[3]};
    guard_->write(&State::pos_lo, slot * sizeof fresh, fresh, sizeof fresh);
  }
  write_real4(&State::pos, slot, at[0], at[1], at[2], p[3]);
}

void Simulation::set_membrane(const MembraneSetting& m) {
  const Membrane& mem = model_->scene().membrane;
  if (mem.count() == 0) throw std::logic_error("set_membrane: the scene has no membrane");
  // a bond's dashpot: the fraction of critical for the reduced mass m/2
  const double mass = model_->scene().mass(model_->scene().particles[size_t(mem.first)]);
  const auto dashpot = [&](double k) { return 2 * mem.damping * std::sqrt(k * mass / 2); };
  write_real4(&State::membrane, 0, m.pressure, m.held ? 1 : 0, m.k_hoop, m.k_axial);
  write_real4(&State::membrane, 1, m.rest_hoop, m.rest_axial, dashpot(m.k_hoop), dashpot(m.k_axial));
  const Vec3& o = model_->origin();
  write_real4(&State::membrane, 3, m.axis_x - o[0], m.axis_y - o[1], 0, 0);
}

Simulation::MembraneSetting Simulation::membrane_setting() {
  if (model_->scene().membrane.count() == 0)
    throw std::logic_error("membrane_setting: the scene has no membrane");
  guard_->before_reading();
  const auto a = read_real4(*model_, state_->membrane, 0);
  const auto b = read_real4(*model_, state_->membrane, 1);
  const auto c = read_real4(*model_, state_->membrane, 3);
  const Vec3& o = model_->origin();
  return {a[0], a[1] != 0, b[0], b[1], a[2], a[3], c[0] + o[0], c[1] + o[1]};
}

void Simulation::place_particles(size_t first, const std::vector<Vec3>& at) {
  const size_t n = static_cast<size_t>(model_->particles());
  if (first > n || at.size() > n - first)
    throw std::out_of_range("place_particles: particles " + std::to_string(first) + " to " +
                            std::to_string(first + at.size()) + " do not all exist");
  if (at.empty()) return;
  guard_->before_reading();
  const size_t m = at.size();
  const bool dbl = model_->config().double_precision;
  std::vector<double> pos = read_reals(*model_, state_->pos, 4 * (first + m));
  std::vector<double> vel = read_reals(*model_, state_->vel, 4 * (first + m));
  std::vector<double> omega = read_reals(*model_, state_->omega, 4 * (first + m));
  RealPacker p(dbl), v(dbl), w(dbl);
  std::vector<float> lo;
  const Vec3& o = model_->origin();
  for (size_t k = 0; k < m; ++k) {
    const size_t i = first + k;
    const double rel[3] = {at[k][0] - o[0], at[k][1] - o[1], at[k][2] - o[2]};
    p.put4(rel[0], rel[1], rel[2], pos[4 * i + 3]);
    v.put4(0, 0, 0, vel[4 * i + 3]);      // w: the mass
    w.put4(0, 0, 0, omega[4 * i + 3]);    // w: the material
    for (double x : rel) lo.push_back(float_remainder(x));
    lo.push_back(0);
  }
  guard_->write(&State::pos, first * p.size() / m, p.data(), p.size());
  guard_->write(&State::vel, first * v.size() / m, v.data(), v.size());
  guard_->write(&State::omega, first * w.size() / m, w.data(), w.size());
  if (!dbl) guard_->write(&State::pos_lo, first * 4 * sizeof(float), lo.data(), lo.size() * sizeof(float));
  guard_->rebuild_lists();
}

void Simulation::scale_radii(double factor) {
  if (model_->clumps() > 0) throw std::logic_error("scale_radii: the scene has clumps");
  guard_->before_reading();
  const size_t n = static_cast<size_t>(model_->particles());
  std::vector<double> pos = read_reals(*model_, state_->pos, 4 * n);
  std::vector<double> vel = read_reals(*model_, state_->vel, 4 * n);
  RealPacker p(model_->config().double_precision), v(model_->config().double_precision);
  const double cube = factor * factor * factor;
  for (size_t i = 0; i < n; ++i) {
    p.put4(pos[4 * i], pos[4 * i + 1], pos[4 * i + 2], pos[4 * i + 3] * factor);
    v.put4(vel[4 * i], vel[4 * i + 1], vel[4 * i + 2], vel[4 * i + 3] * cube);
  }
  guard_->write(&State::pos, 0, p.data(), p.size());
  guard_->write(&State::vel, 0, v.data(), v.size());
  guard_->rebuild_lists();
}

void Simulation::set_wall_point(int wall, const Vec3& p) {
  check_wall(*model_, wall, "set_wall_point");
  const Vec3& o = model_->origin();
  double rel[3];
  for (int a = 0; a < 3; ++a) rel[a] = p[a] - o[a];
  write_real4(&State::wall_point, wall, rel[0], rel[1], rel[2], 0);
  if (!model_->config().double_precision) {
    const float lo[4] = {float_remainder(rel[0]), float_remainder(rel[1]),
                         float_remainder(rel[2]), 0};
    guard_->write(&State::wall_point_lo, wall * sizeof lo, lo, sizeof lo);
  }
  // a jump is no travel the broad phase can bound: the wall masks and slots
  // are built anew before the next step's forces (walls.cl); logged, so a
  // replay does it too
  guard_->rebuild_lists();
}

std::vector<Simulation::WallMean> Simulation::read_wall_means() {
  std::vector<WallMean> out;
  if (!model_->config().servo) return out;
  const int nw = model_->walls();
  guard_->before_reading();
  const std::vector<double> sums = read_reals(*model_, state_->wall_mean, size_t(nw) * 4);
  for (int w = 0; w < nw; ++w) {
    const double* r = &sums[4 * size_t(w)];
    WallMean m;
    m.steps = static_cast<std::int64_t>(r[3]);
    for (int k = 0; k < 3; ++k) m.force[k] = m.steps > 0 ? r[k] / r[3] : 0;
    out.push_back(m);
  }
  std::vector<unsigned char> zero(state_->wall_mean.bytes, 0);
  guard_->write(&State::wall_mean, 0, zero.data(), zero.size());
  return out;
}

bool advance_through_contact(Simulation& sim, int i, std::int64_t max_steps) {
  bool touched = false;
  for (std::int64_t k = 0; k < max_steps; ++k) {
    sim.advance(1);
    const int c = sim.snapshot().contacts[i];
    touched = touched || c > 0;
    if (touched && c == 0) return true;
  }
  return false;
}

}  // namespace simsols
