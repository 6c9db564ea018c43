#include "solver/apparatus/shear_box/shear_programme.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "solver/apparatus/cell/platen_servo.h"
#include "solver/apparatus/shear_box/shear_box.h"
#include "solver/apparatus/cell/stage_checks.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRad = 180.0 / kPi;

// Shares of the settle and consolidate caps the paper's tests take before
// their end criteria hold (for progress estimates only).
constexpr double kSettleShare = 0.3;
constexpr double kConsolidateShare = 0.3;

// Equilibrium at the end of consolidation (consolidated()): the reaction's
// error, the beads' RMS speed and the platen's speed, the last two as
// fractions of the shear speed.
constexpr double kEquilibriumForce = 0.01;
constexpr double kEquilibriumBeads = 0.1;
constexpr double kEquilibriumPlaten = 0.01;

const ShearBox& box_of(const Simulation& sim) {
  const ShearBox* box = sim.scene().apparatus_as<ShearBox>();
  if (!box) throw std::invalid_argument("ShearProgramme: the scene has no shear box");
  return *box;
}

}  // namespace

const char* phase_name(ShearPhase p) {
  switch (p) {
    case ShearPhase::Settle: return "settle";
    case ShearPhase::Consolidate: return "consolidate";
    case ShearPhase::Shear: return "shear";
    case ShearPhase::Done: return "done";
  }
  return "?";
}

ShearProgramme::ShearProgramme(Simulation& sim) : sim_(sim), box_(box_of(sim)) {
  stats_ = specimen_stats(sim.scene(), box_.wall_material);
  diameter_ = stats_.diameter;
  density_ = stats_.density;
  sigma_target_ = box_.normal_stress;
  // A quarter of a layer of touching beads over the platen's area: on its
  // contacts (one per d^2) the platen rings like a bead on four, no faster
  // than a bead in the packing (about six), so the step that resolves the
  // beads resolves it; light enough to follow a collapse of the specimen
  // within a fraction of a row (docs/shear-box.md).
  platen_mass_ = box_.platen_mass > 0 ? box_.platen_mass
                                      : density_ * kPi * diameter_ * shear_area(box_) / 24;
  tune_servo();
}

// Automatic servo settings (platen_servo.h), retuned when the target
// changes: a gain tuned at 50 kPa is twice as sharp at 400 kPa, at the limit
// of the loop's stability (docs/shear-box.md), and the platen rang from step
// to step (stability case 6).
void ShearProgramme::tune_servo() {
  const PlatenServo p = tune_platen_servo(stats_, shear_area(box_), sigma_target_, sim_.dt(),
                                          box_.servo_gain, box_.servo_integral_time);
  gain_ = p.gain;
  integral_time_ = p.integral_time;
}

double ShearProgramme::shear_speed_for(double height) const {
  if (speed_override_ > 0) return speed_override_;
  return box_.shear_speed > 0 ? box_.shear_speed
                              : speed_for_inertial_number(box_.inertial_number, height,
                                                          diameter_, density_, sigma_target_);
}

double ShearProgramme::inertial_number() const {
  return height0_ > 0 ? inertial_number_of(speed_, height0_, diameter_, density_, sigma_target_)
                      : 0;
}

std::int64_t ShearProgramme::steps_for(double seconds) const {
  return std::max<std::int64_t>(1, std::llround(seconds / sim_.dt()));
}

void ShearProgramme::apply_servo(bool on) {
  WallServo s;
  s.enabled = on;
  s.target_force = sigma_target_ * shear_area(box_);
  s.gain = gain_;
  s.max_speed = box_.servo_max_speed;
  s.integral_time = integral_time_;
  s.mass = loaded_ ? platen_mass_ : 0;
  sim_.set_servo(box_.first_wall + kPlaten, s);
}

// The floating upper half (ShearBox::upper_half): its frame a dead weight
// of upper_half_weight along -z with the platen's mass (the same contact
// count reasoning), stopped where the halves meet (the gap closed), its
// four side plates members of the frame's group (walls.cl). Off: held.
void ShearProgramme::float_upper_half(bool on) {
  if (box_.upper_half != ShearBox::UpperHalf::Floating) return;
  const int frame = box_.first_wall + kUpperFrame;
  WallServo lead;
  lead.enabled = on;
  lead.target_force = box_.upper_half_weight;
  lead.mass = platen_mass_;
  lead.stop = box_.gap;
  sim_.set_servo(frame, lead);
  for (int w = kUpperX0; w <= kUpperY1; ++w) {
    WallServo member;
    member.leader = on ? frame : -1;
    sim_.set_servo(box_.first_wall + w, member);
  }
}

double ShearProgramme::upper_half_rise() const {
  const int frame = box_.first_wall + kUpperFrame;
  return sim_.wall_point(frame)[2] - sim_.scene().walls[frame].point[2];
}

void ShearProgramme::set_normal_stress(double pascals) {
  if (!(pascals > 0) || !std::isfinite(pascals))
    throw std::invalid_argument("normal stress must be > 0 Pa");
  sigma_target_ = pascals;
  tune_servo();
  if (phase_ == ShearPhase::Consolidate || phase_ == ShearPhase::Shear) apply_servo(true);
  if (phase_ != ShearPhase::Shear || speed_override_ > 0 || box_.shear_speed > 0) return;
  retime_rows(shear_speed_for(specimen_height()));
}

double ShearProgramme::specimen_height() const {
  return sim_.wall_point(box_.first_wall + kPlaten)[2] -
         sim_.wall_point(box_.first_wall + kFloor)[2];
}

void ShearProgramme::start_shear() {
  hold_ = false;
  if (ready_to_shear()) enter(ShearPhase::Shear);
}

void ShearProgramme::set_shear_speed(double v) {
  if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("shear speed must be > 0 m/s");
  speed_override_ = v;
  if (phase_ == ShearPhase::Shear) retime_rows(v);
}

void ShearProgramme::retime_rows(double v) {
  speed_ = v;
  move_lower_half(v);
  const double done = rows_.empty() ? 0 : rows_.back().displacement;
  const int left = std::max(1, box_.rows + 1 - static_cast<int>(rows_.size()));
  const double remaining = std::max(0.0, box_.shear_displacement - done);
  row_steps_ = std::max<std::int64_t>(1, std::llround(remaining / (v * sim_.dt()) / left));
  next_row_ = sim_.steps() + row_steps_;
}

void ShearProgramme::move_lower_half(double vx) {
  for (int w = kFloor; w <= kLowerLast; ++w) sim_.set_wall_velocity(box_.first_wall + w, {vx, 0, 0});
}

void ShearProgramme::enter(ShearPhase p) {
  const std::int64_t now = sim_.steps();
  const double elapsed = (now - phase_start_) * sim_.dt();
  if (phase_ == ShearPhase::Settle) settle_seconds_ = elapsed;
  if (phase_ == ShearPhase::Consolidate) consolidate_seconds_ = elapsed;
  phase_ = p;
  phase_start_ = now;
  quiet_checks_ = 0;
  preparation_friction(sim_, box_.specimen, p == ShearPhase::Settle);
  next_check_ = now + std::max<std::int64_t>(50, steps_for(0.5e-3));
  switch (p) {
    case ShearPhase::Settle:
      apply_servo(false);
      break;
    case ShearPhase::Consolidate: {
      // The platen is lowered onto the settled specimen (a tenth of a
      // diameter above its highest bead) and its servo switched on.
      lower_platen_onto_specimen(sim_, box_.first_wall + kPlaten, 0.1 * diameter_);
      sim_.read_servo(box_.first_wall + kPlaten);
      loaded_ = false;
      apply_servo(true);
      break;
    }
    case ShearPhase::Shear: {
      x0_ = sim_.wall_point(box_.first_wall + kFloor)[0];
      z0_ = sim_.wall_point(box_.first_wall + kPlaten)[2];
      height0_ = specimen_height();
      speed_ = shear_speed_for(height0_);
      shear_steps_ = std::max<std::int64_t>(
          box_.rows, std::llround(box_.shear_displacement / (speed_ * sim_.dt())));
      row_steps_ = std::max<std::int64_t>(1, shear_steps_ / box_.rows);
      shear_steps_ = row_steps_ * box_.rows;
      measure_row();  // at rest: the means over the last equilibrium check
      if (dead_weight() && !loaded_) {  // consolidation ended on its time cap before the
        loaded_ = true;                 // servo handed over: the hanger takes the load now,
        apply_servo(true);              // so a dead-weight box always shears under its weight
      }
      move_lower_half(speed_);
      float_upper_half(true);
      next_row_ = now + row_steps_;
      break;
    }
    case ShearPhase::Done:
      move_lower_half(0);
      float_upper_half(false);
      apply_servo(false);
      break;
  }
}

bool ShearProgramme::settled() {
  const double elapsed = (sim_.steps() - phase_start_) * sim_.dt();
  return settled_under_gravity(sim_, stats_, elapsed, box_.settle_time);
}

// Equilibrium under the load: the mean reaction since the last check
// within 1 % of the target, the beads' RMS speed and the platen's speed
// small against the shear speed, twice in a row. With a dead weight the
// servo that brought the load hands it over at the first such state, and
// equilibrium is then sought again under the weight alone.
bool ShearProgramme::consolidated() {
  const std::int64_t now = sim_.steps();
  const double elapsed = (now - phase_start_) * sim_.dt();
  const int platen = box_.first_wall + kPlaten;
  const Simulation::ServoReading r = sim_.read_servo(platen);
  if (elapsed >= box_.consolidate_time || equilibrium(r.mean)) return true;
  sim_.read_wall_means();  // restart the means: the row at rest uses the last window
  return false;
}

bool ShearProgramme::equilibrium(double reaction) {
  const int platen = box_.first_wall + kPlaten;
  const double target = sigma_target_ * shear_area(box_);
  const Observables o = sim_.observe();
  const double v_rms = rms_bead_speed(o, stats_);
  const double v_platen = std::fabs(sim_.wall_velocity(platen)[2]);
  const double v_shear = shear_speed_for(specimen_height());
  const bool quiet = std::fabs(reaction - target) < kEquilibriumForce * target &&
                     v_rms < kEquilibriumBeads * v_shear &&
                     v_platen < kEquilibriumPlaten * v_shear;
  quiet_checks_ = quiet ? quiet_checks_ + 1 : 0;
  if (quiet_checks_ < 2) return false;
  if (dead_weight() && !loaded_) {
    loaded_ = true;
    apply_servo(true);
    quiet_checks_ = 0;
    return false;
  }
  return true;
}

void ShearProgramme::measure_row() {
  const auto means = sim_.read_wall_means();
  sim_.read_servo(box_.first_wall + kPlaten);
  const int f = box_.first_wall;
  ShearRow row;
  row.sigma_target = sigma_target_;
  row.time = sim_.time();
  row.step = sim_.steps();
  const Vec3 floor = sim_.wall_point(f + kFloor);
  const Vec3 platen = sim_.wall_point(f + kPlaten);
  row.displacement = floor[0] - x0_;
  for (int w = kFloor; w <= kLowerLast; ++w) row.shear_force -= means[f + w].force[0];
  for (int w = kUpperX0; w <= kPlaten; ++w) row.shear_force_upper += means[f + w].force[0];
  row.normal_force = means[f + kPlaten].force[2];
  const double area = shear_area(box_);
  row.tau = row.shear_force / area;
  row.tau_corrected = row.shear_force / shear_area_corrected(box_, row.displacement);
  row.sigma = row.normal_force / area;
  // what the upper half's side plates carry of the load by friction (the
  // beads drag them down: a negative z-force) does not reach the shear
  // plane; what they drag up (a dilating specimen) adds to it. The upper
  // frame is left out: the beads under it are the lower half's.
  double upper_z = 0;
  for (int w = kUpperX0; w <= kUpperY1; ++w) upper_z += means[f + w].force[2];
  row.sigma_plane = (row.normal_force + upper_z) / area;
  row.dilation = platen[2] - z0_;
  row.cap_tilt = sim_.wall_tilt(f + kPlaten).angle;
  row.friction_angle = row.sigma > 0 ? std::atan(row.tau / row.sigma) * kRad : 0;
  const Observables o = sim_.observe();
  row.coordination = o.particles > 0 ? o.contacts / o.particles : 0;
  row.kinetic_energy = o.kinetic();
  const double height = platen[2] - floor[2];
  row.inertial_number =
      row.sigma > 0 ? inertial_number_of(speed_, height, diameter_, density_, row.sigma) : 0;
  // Escaped beads: centre outside the lower frame (below the split), the
  // upper frame (above it) or both (in the gap band), or above the platen.
  const ParticleSnapshot snap = sim_.snapshot();
  const double zs = box_.split_height, g = box_.gap / 2, L = box_.length, W = box_.width;
  const double dx = row.displacement;
  for (const Vec3& p : snap.position) {
    const double lo_x = p[2] > zs + g ? 0 : p[2] < zs - g ? dx : std::min(0.0, dx);
    const double hi_x = p[2] > zs + g ? L : p[2] < zs - g ? L + dx : std::max(L, L + dx);
    const bool in = p[0] >= lo_x && p[0] <= hi_x && p[1] >= 0 && p[1] <= W &&
                    p[2] >= floor[2] && p[2] <= platen[2];
    row.outside += in ? 0 : 1;
  }
  rows_.push_back(row);
}

bool ShearProgramme::advance(std::int64_t max_steps) {
  if (!started_) {
    started_ = true;
    phase_start_ = sim_.steps();
    enter(box_.settle_time > 0 ? ShearPhase::Settle : ShearPhase::Consolidate);
  }
  std::int64_t left = max_steps;
  while (left > 0 && phase_ != ShearPhase::Done) {
    const std::int64_t event = phase_ == ShearPhase::Shear ? next_row_ : next_check_;
    const std::int64_t n = std::min(left, event - sim_.steps());
    if (n > 0) sim_.advance(n);
    left -= std::max<std::int64_t>(n, 0);
    if (sim_.steps() < event) break;
    const std::int64_t every = std::max<std::int64_t>(50, steps_for(0.5e-3));
    switch (phase_) {
      case ShearPhase::Settle:
        if (settled()) enter(ShearPhase::Consolidate);
        else next_check_ = sim_.steps() + every;
        return false;
      case ShearPhase::Consolidate:
        ready_ = ready_ || consolidated();
        if (ready_ && !hold_) enter(ShearPhase::Shear);
        else next_check_ = sim_.steps() + every;
        return false;
      case ShearPhase::Shear:
        measure_row();
        next_row_ = sim_.steps() + row_steps_;
        if (static_cast<int>(rows_.size()) > box_.rows) enter(ShearPhase::Done);
        return true;
      case ShearPhase::Done: break;
    }
  }
  return false;
}

// The preparation phases end when their criteria hold (settled(),
// consolidated()), usually well before their caps; the estimates use the
// shares of the caps the paper's tests take (kSettleShare, kConsolidateShare)
// and the shear its exact step count once it has begun.
ShearProgramme::StepCount ShearProgramme::step_count() const {
  const double dt = sim_.dt();
  const double elapsed = started_ ? double(sim_.steps() - phase_start_) : 0;
  const double settle = box_.settle_time / dt * kSettleShare;
  const double consolidate = box_.consolidate_time / dt * kConsolidateShare;
  const double shear = shear_steps_ > 0 ? double(shear_steps_)
                                        : box_.shear_displacement /
                                              (shear_speed_for(stats_.layers * diameter_) * dt);
  const double settled = settle_seconds_ / dt, consolidated = consolidate_seconds_ / dt;
  StepCount c;
  switch (phase_) {
    case ShearPhase::Settle:
      c.done = elapsed;
      c.total = std::max(settle, elapsed) + consolidate + shear;
      break;
    case ShearPhase::Consolidate:
      c.done = settled + elapsed;
      c.total = settled + std::max(consolidate, elapsed) + shear;
      break;
    case ShearPhase::Shear:
      c.done = settled + consolidated + elapsed;
      c.total = settled + consolidated + std::max(shear, elapsed);
      break;
    case ShearPhase::Done: c.done = c.total = settled + consolidated + double(shear_steps_); break;
  }
  return c;
}

std::string ShearProgramme::status() const {
  char buf[200];
  if (phase_ == ShearPhase::Shear && !rows_.empty()) {
    const ShearRow& r = rows_.back();
    std::snprintf(buf, sizeof buf, "shear dx = %.3f/%.3f mm, tau/sigma = %.3f, sigma = %.1f kPa",
                  r.displacement * 1e3, box_.shear_displacement * 1e3,
                  r.sigma > 0 ? r.tau / r.sigma : 0, r.sigma * 1e-3);
  } else {
    std::snprintf(buf, sizeof buf, "%s t = %.2f ms", phase_name(phase_),
                  (sim_.steps() - phase_start_) * sim_.dt() * 1e3);
  }
  return buf;
}

std::string ShearProgramme::caption() const {
  char buf[200];
  if (rows_.empty()) {
    std::snprintf(buf, sizeof buf, "%s", phase_name(phase_));
  } else {
    const ShearRow& r = rows_.back();
    std::snprintf(buf, sizeof buf, "δ = %.2f mm, τ/σ = %.3f, σ = %.1f kPa", r.displacement * 1e3,
                  r.sigma > 0 ? r.tau / r.sigma : 0, r.sigma * 1e-3);
  }
  return buf;
}

ShearSummary ShearProgramme::summary() const {
  ShearSummary s;
  s.normal_stress_target = sigma_target_;
  s.shear_speed = speed_;
  s.specimen_height = height0_;
  s.bead_diameter = diameter_;
  s.settle_time = settle_seconds_;
  s.consolidate_time = consolidate_seconds_;
  s.platen_mass = platen_mass();
  s.upper_half_floating = box_.upper_half == ShearBox::UpperHalf::Floating;
  s.upper_half_rise = upper_half_rise();
  s.cap_tilting = box_.cap == ShearBox::Cap::Tilting;
  analyse_shear_rows(rows_, s);
  return s;
}

std::string ShearProgramme::save_state() const {
  std::ostringstream o;
  o.precision(17);
  o << "shear_test 4\n"
    << started_ << ' ' << static_cast<int>(phase_) << ' ' << phase_start_ << ' ' << next_check_
    << ' ' << next_row_ << ' ' << row_steps_ << ' ' << shear_steps_ << ' ' << quiet_checks_
    << '\n'
    << sigma_target_ << ' ' << speed_ << ' ' << gain_ << ' ' << integral_time_ << ' ' << x0_
    << ' ' << z0_ << ' ' << height0_ << ' ' << settle_seconds_ << ' ' << consolidate_seconds_
    << '\n'
    << hold_ << ' ' << ready_ << ' ' << speed_override_ << ' ' << loaded_ << '\n'
    << rows_.size() << '\n';
  for (const ShearRow& r : rows_)
    o << r.time << ' ' << r.step << ' ' << r.displacement << ' ' << r.shear_force << ' '
      << r.shear_force_upper << ' ' << r.tau << ' ' << r.tau_corrected << ' ' << r.normal_force
      << ' ' << r.sigma << ' ' << r.dilation << ' ' << r.friction_angle << ' ' << r.coordination
      << ' ' << r.kinetic_energy << ' ' << r.inertial_number << ' ' << r.outside << ' '
      << r.sigma_target << ' ' << r.sigma_plane << '\n';
  return o.str();
}

void ShearProgramme::restore_state(const std::string& text) {
  std::istringstream in(text);
  std::string tag;
  int version = 0, phase = 0;
  size_t count = 0;
  in >> tag >> version;
  if (tag != "shear_test" || version < 1 || version > 4)
    throw ReadError("the checkpoint holds no shear-test state");
  in >> started_ >> phase >> phase_start_ >> next_check_ >> next_row_ >> row_steps_ >>
      shear_steps_ >> quiet_checks_ >> sigma_target_ >> speed_ >> gain_ >> integral_time_ >>
      x0_ >> z0_ >> height0_ >> settle_seconds_ >> consolidate_seconds_;
  hold_ = ready_ = loaded_ = false;
  speed_override_ = 0;
  if (version >= 2) in >> hold_ >> ready_ >> speed_override_;  // version 1: no bench control
  if (version >= 3) in >> loaded_;  // before: a servo throughout
  in >> count;
  if (!in || phase < 0 || phase > 3) throw ReadError("malformed shear-test state");
  phase_ = static_cast<ShearPhase>(phase);
  preparation_friction(sim_, box_.specimen, started_ && phase_ == ShearPhase::Settle);
  rows_.assign(count, {});
  for (ShearRow& r : rows_) {
    in >> r.time >> r.step >> r.displacement >> r.shear_force >> r.shear_force_upper >> r.tau >>
        r.tau_corrected >> r.normal_force >> r.sigma >> r.dilation >> r.friction_angle >>
        r.coordination >> r.kinetic_energy >> r.inertial_number >> r.outside;
    if (version >= 3) in >> r.sigma_target;
    if (version >= 4) in >> r.sigma_plane;  // before: not recorded (0)
  }
  if (!in) throw ReadError("malformed shear-test rows");
}

std::string ShearProgramme::rows_csv() const { return shear_rows_csv(rows_); }

std::string ShearProgramme::summary_text(double wall_seconds) const {
  ShearSummary s = summary();
  s.wall_seconds = wall_seconds;
  return shear_summary_text(s);
}

std::string ShearProgramme::describe() const {
  char buf[128];
  std::snprintf(buf, sizeof buf, "servo gain %.3g m/(s N), integral time %.3g s", gain_,
                integral_time_);
  return buf;
}

std::string ShearProgramme::measuring_line() const {
  char buf[192];
  std::snprintf(buf, sizeof buf,
                "shearing at %.4g mm/s (inertial number %.2g at the start; quasi-static below "
                "1e-3), specimen height %.2f mm",
                speed_ * 1e3, inertial_number(), summary().specimen_height * 1e3);
  return buf;
}

}  // namespace simsols
