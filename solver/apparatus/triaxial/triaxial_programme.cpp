#include "solver/apparatus/triaxial/triaxial_programme.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "solver/apparatus/specimen/packing.h"
#include "solver/apparatus/cell/stage_checks.h"
#include "solver/apparatus/triaxial/membrane_cell.h"
#include "solver/apparatus/triaxial/triaxial.h"
#include "solver/core/stress.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr double kCheckSeconds = 0.5e-3;
constexpr double kForceError = 0.01;
constexpr double kBeadsInertial = 1e-4;
constexpr double kHandOverWait = 10;  // consolidate_times the plates may take before the membrane takes over
constexpr double kSettleShare = 0.3, kConsolidateShare = 0.3;  // progress estimates

const Triaxial& triaxial_of(const Simulation& sim) {
  const Triaxial* t = sim.scene().apparatus_as<Triaxial>();
  if (!t) throw std::invalid_argument("TriaxialProgramme: the scene has no triaxial cell");
  return *t;
}

}  // namespace

TriaxialProgramme::TriaxialProgramme(Simulation& sim) : sim_(sim), tri_(triaxial_of(sim)) {
  stats_ = specimen_stats(sim.scene(), tri_.wall_material);
  membrane_ = tri_.cell == Triaxial::Cell::Membrane;
  sigma3_ = tri_.confining_stress;
  rate_ = tri_.strain_rate > 0 ? tri_.strain_rate
                               : triaxial_strain_rate(tri_.inertial_number, stats_.diameter,
                                                      stats_.density, tri_.confining_stress);
}

const char* TriaxialProgramme::stage_name() const {
  switch (stage_) {
    case Stage::Settle: return "settle";
    case Stage::Consolidate: return "consolidate";
    case Stage::Compress: return "compress";
    case Stage::Done: return "done";
  }
  return "?";
}

std::int64_t TriaxialProgramme::check_every() const {
  return std::max<std::int64_t>(50, std::llround(kCheckSeconds / sim_.dt()));
}

TriaxialProgramme::Cell TriaxialProgramme::cell() {
  const int f = tri_.first_wall;
  return {sim_.wall_point(f + kTriX0)[0], sim_.wall_point(f + kTriX1)[0],
          sim_.wall_point(f + kTriY0)[1], sim_.wall_point(f + kTriY1)[1],
          sim_.wall_point(f + kTriFloor)[2], sim_.wall_point(f + kTriPlaten)[2]};
}

std::array<double, 3> TriaxialProgramme::targets(double sigma_z) const {
  const double s3 = sigma3_;
  if (stage_ != Stage::Compress) return {s3, s3, s3};
  switch (tri_.path) {
    case Triaxial::Path::ConstantSigma3: return {s3, s3, sigma_z};
    case Triaxial::Path::ConstantP: {
      const double lateral = std::max(0.05 * s3, (3 * s3 - sigma_z) / 2);
      return {lateral, lateral, sigma_z};
    }
    case Triaxial::Path::TrueTriaxial:
      return {s3, s3 + tri_.b_value * std::max(0.0, sigma_z - s3), sigma_z};
  }
  return {s3, s3, sigma_z};
}

// Each servo plate's force target and tuning for the stresses, on the
// plates' current areas.
void TriaxialProgramme::apply_servos(const std::array<double, 3>& stress, bool platen,
                                     const Wrapped* shape) {
  const Cell c = cell();
  // under the membrane the platen's area is read from its beads, only when the platen is set
  const double platen_area = !platen || !wrapped() ? c.lx() * c.ly()
                             : shape               ? shape->area
                                                   : wrapped_shape(c).area;
  const double area[3] = {c.ly() * c.lz(), c.lx() * c.lz(), platen_area};
  const double extent[3] = {c.lx(), c.ly(), c.lz()};
  const int walls[3][2] = {{kTriX0, kTriX1}, {kTriY0, kTriY1}, {kTriPlaten, -1}};
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == 2 && !platen) continue;
    if (axis < 2 && wrapped()) continue;  // the membrane holds the sides
    SpecimenStats s = stats_;
    s.layers = std::max(1.0, extent[axis] / stats_.diameter);
    const PlatenServo tuned = tune_platen_servo(s, area[axis], stress[axis], sim_.dt(),
                                                tri_.servo_gain, tri_.servo_integral_time);
    WallServo servo;
    servo.enabled = true;
    servo.target_force = stress[axis] * area[axis];
    servo.gain = tuned.gain;
    servo.max_speed = tri_.servo_max_speed;
    servo.integral_time = tuned.integral_time;
    for (int w : walls[axis])
      if (w >= 0) sim_.set_servo(tri_.first_wall + w, servo);
  }
}

// The side plates hand the specimen to the membrane: its beads wrapped
// where the plates touched it (membrane_cell.h), under the confining
// stress; the plates step back out of reach, their servos off.
void TriaxialProgramme::wrap_membrane(const Cell& c) {
  const Membrane& m = sim_.scene().membrane;
  const double rm = sim_.scene().particles[size_t(m.first)].radius;
  const double pitch = (c.lz() - 2 * rm) / (m.rows - 1);
  if (pitch > 2 * rm) {  // the rows would not touch: the grains pass between them
    char what[400];
    std::snprintf(what, sizeof what,
                  "the membrane's %d rows were planned for a specimen of porosity %.2g; the plates "
                  "consolidated one %.1f mm tall and %.1f x %.1f mm across (e = %.2f), over which "
                  "they would stand %.1f mm apart, farther than their diameter %.1f mm, and the "
                  "grains would pass between them: let the pour settle longer, or prepare it denser",
                  m.rows, kMembranePlannedPorosity, c.lz() * 1e3, c.lx() * 1e3, c.ly() * 1e3,
                  c.lx() * c.ly() * c.lz() / stats_.volume - 1, pitch * 1e3, 2 * rm * 1e3);
    throw InputError("membrane_too_short", sim_.scene().source_path, 0, "triaxial.settle_time", what);
  }
  const MembraneWrap w = wrap_cuboid(m, rm, sigma3_, {c.x0, c.x1, c.y0, c.y1, c.z0, c.z1});
  sim_.place_particles(size_t(m.first), w.positions);
  sim_.set_membrane(w.setting);
  wrap_step_ = sim_.steps();
  const double away = c.lx() + c.ly();
  for (int k = kTriX0; k <= kTriY1; ++k) {
    const int wall = tri_.first_wall + k;
    const Vec3 n = sim_.scene().walls[size_t(wall)].normal;  // into the cell
    const Vec3 at = sim_.wall_point(wall);
    sim_.set_servo(wall, WallServo{});
    sim_.set_wall_point(wall, {at[0] - away * n[0], at[1] - away * n[1], at[2] - away * n[2]});
  }
}

TriaxialProgramme::Wrapped TriaxialProgramme::wrapped_shape(const Cell& c) {
  const Membrane& m = sim_.scene().membrane;
  const double rm = sim_.scene().particles[size_t(m.first)].radius;
  const MembraneShape s = measure_membrane(sim_.snapshot().position, m, rm, c.z0, c.z1,
                                           sim_.membrane_setting());
  return {s.volume, s.area, s.hoop_stress};
}

void TriaxialProgramme::enter(Stage s) {
  const std::int64_t now = sim_.steps();
  const double elapsed = (now - stage_start_) * sim_.dt();
  if (stage_ == Stage::Settle) settle_seconds_ = elapsed;
  if (stage_ == Stage::Consolidate) consolidate_seconds_ = elapsed;
  stage_ = s;
  stage_start_ = now;
  quiet_checks_ = 0;
  consolidated_ = false;
  preparation_friction(sim_, tri_.specimen, s == Stage::Settle);
  next_check_ = now + check_every();
  const int platen = tri_.first_wall + kTriPlaten;
  if (s == Stage::Settle || s == Stage::Done) {
    for (int w = kTriX0; w <= kTriPlaten; ++w) {
      sim_.set_servo(tri_.first_wall + w, WallServo{});
      sim_.set_wall_velocity(tri_.first_wall + w, {0, 0, 0});
    }
    return;
  }
  if (s == Stage::Consolidate) {
    lower_platen_onto_specimen(sim_, tri_.first_wall + kTriPlaten, 0.1 * stats_.diameter);
    sim_.read_wall_means();
    apply_servos(targets(0), true);
    return;
  }
  // Compress: the row at rest, then the platen moves down.
  const Cell c = cell();
  h0_ = c.lz();
  v0_ = wrapped() ? wrapped_shape(c).volume : c.lx() * c.ly() * c.lz();
  compress_steps_ = std::max<std::int64_t>(
      tri_.rows, std::llround(tri_.axial_strain / (rate_ * sim_.dt())));
  row_steps_ = std::max<std::int64_t>(1, compress_steps_ / tri_.rows);
  compress_steps_ = row_steps_ * tri_.rows;
  last_sigma_z_ = sigma3_;
  measure_row(&consolidated_stress_);
  sim_.set_servo(platen, WallServo{});
  sim_.set_wall_velocity(platen, {0, 0, -rate_ * h0_});
  next_row_ = now + row_steps_;
}

std::array<double, 3> TriaxialProgramme::wall_stresses(const Cell& c, const Wrapped* shape) {
  const auto means = sim_.read_wall_means();
  const int f = tri_.first_wall;
  if (wrapped()) {
    const Wrapped w = shape ? *shape : wrapped_shape(c);
    const double side = sigma3_ + w.hoop_stress;
    return {side, side, means[f + kTriPlaten].force[2] / w.area};
  }
  const double fx = means[f + kTriX1].force[0] - means[f + kTriX0].force[0];
  const double fy = means[f + kTriY1].force[1] - means[f + kTriY0].force[1];
  return {fx / (2 * c.ly() * c.lz()), fy / (2 * c.lx() * c.lz()),
          means[f + kTriPlaten].force[2] / (c.lx() * c.ly())};
}

bool TriaxialProgramme::consolidated() {
  const Cell c = cell();
  const Wrapped w = wrapped() ? wrapped_shape(c) : Wrapped{};
  const std::array<double, 3> s = wall_stresses(c, wrapped() ? &w : nullptr);
  consolidated_stress_ = s;
  const double p0 = sigma3_;
  const Observables o = sim_.observe();
  const double v_rms = rms_bead_speed(o, stats_);
  const double scale = c.lz() / stats_.diameter * std::sqrt(p0 / stats_.density);
  // the plates' stresses; a membrane holds the sides at the cell pressure
  bool at_stress = true;
  for (int axis = wrapped() ? 2 : 0; axis < 3; ++axis)
    at_stress = at_stress && std::fabs(s[size_t(axis)] - p0) < kForceError * p0;
  const bool quiet = at_stress && v_rms < kBeadsInertial * scale;
  quiet_checks_ = quiet ? quiet_checks_ + 1 : 0;
  const std::int64_t since = wrapped() ? wrap_step_ : stage_start_;
  const double elapsed = (sim_.steps() - since) * sim_.dt();
  const bool timed_out = elapsed >= tri_.consolidate_time;
  const bool done = quiet_checks_ >= 2 || timed_out;
  // what the lab's hold reports: a time-out only once the plates are at the stress
  consolidated_ = quiet_checks_ >= 2 || (timed_out && at_stress);
  // the membrane is wrapped about a specimen the plates hold at the stress,
  // or, failing that, after ten times consolidate_time (wrap_membrane
  // refuses a specimen taller than its rows can cover)
  const bool hand_over = consolidated_ || elapsed >= kHandOverWait * tri_.consolidate_time;
  if (membrane_ && !wrapped()) {  // the plates consolidate until they hand over
    if (hand_over) {
      wrap_membrane(c);  // then again under the membrane
      quiet_checks_ = 0;
      consolidated_ = false;
    }
    apply_servos(targets(0), true);
    return false;
  }
  apply_servos(targets(0), true, wrapped() ? &w : nullptr);  // the areas changed
  if (hold_) return false;
  return done;
}

void TriaxialProgramme::set_confining_stress(double pascals) {
  sigma3_ = pascals;
  if (stage_ == Stage::Consolidate) {
    quiet_checks_ = 0;
    consolidated_ = false;
    stage_start_ = sim_.steps();
    apply_servos(targets(0), true);
  } else if (stage_ == Stage::Compress) {
    apply_servos(targets(last_sigma_z_), false);
    if (wrapped()) {
      Simulation::MembraneSetting m = sim_.membrane_setting();
      m.pressure = pascals;
      sim_.set_membrane(m);
    }
  }
}

void TriaxialProgramme::set_strain_rate(double per_second) {
  rate_ = per_second;
  if (stage_ != Stage::Compress) return;
  // The rows stay tri_.axial_strain / tri_.rows apart in strain.
  const double row_strain = tri_.axial_strain / tri_.rows;
  row_steps_ = std::max<std::int64_t>(1, std::llround(row_strain / (rate_ * sim_.dt())));
  compress_steps_ = (sim_.steps() - stage_start_) +
                    row_steps_ * std::max<std::int64_t>(0, tri_.rows + 1 - std::ssize(rows_));
  next_row_ = std::min(next_row_, sim_.steps() + row_steps_);
  sim_.set_wall_velocity(tri_.first_wall + kTriPlaten, {0, 0, -rate_ * h0_});
}

bool TriaxialProgramme::follows_platen() const {
  return tri_.path != Triaxial::Path::ConstantSigma3;
}

// The sides' targets from the platen's stress now (its reaction this step),
// so a constant-p or true-triaxial path is held between rows as well.
void TriaxialProgramme::follow_platen() {
  const Cell c = cell();
  const std::vector<WallReaction> now = sim_.wall_reactions();
  const double sz = now[tri_.first_wall + kTriPlaten].force[2] / (c.lx() * c.ly());
  apply_servos(targets(sz), false);
}

bool TriaxialProgramme::start_compression() {
  if (stage_ != Stage::Consolidate) return false;
  enter(Stage::Compress);
  return true;
}

TriaxialProgramme::AtRest TriaxialProgramme::at_rest() {
  AtRest a;
  const Cell c = cell();
  a.stress = consolidated_stress_;
  a.p = (a.stress[0] + a.stress[1] + a.stress[2]) / 3;
  a.volume = c.lx() * c.ly() * c.lz();
  a.void_ratio = a.volume / stats_.volume - 1;
  a.porosity = 1 - stats_.volume / a.volume;
  const ContactSample sample = sample_contacts(sim_);
  int pairs = 0;
  for (const ContactForce& f : sample.contacts) pairs += f.b >= 0;
  const double n = stats_.count;  // a waiting membrane's beads touch nothing
  a.bead_coordination = n > 0 ? 2.0 * pairs / n : 0;
  return a;
}

void TriaxialProgramme::measure_row(const std::array<double, 3>* at_rest) {
  const Cell c = cell();
  const bool wrap = wrapped();
  const Wrapped w = wrap ? wrapped_shape(c) : Wrapped{c.lx() * c.ly() * c.lz(), c.lx() * c.ly(), 0};
  std::array<double, 3> s = at_rest ? *at_rest : wall_stresses(c, &w);
  const ContactSample sample = sample_contacts(sim_);
  const size_t beads = size_t(stats_.count);
  TriaxialRow r;
  if (wrap) {  // the platen carries the membrane's share too (membrane_cell.h)
    r.membrane_axial = membrane_axial_share(sample, beads, w.volume, c.z0);
    r.membrane_shell = membrane_shell_share(sim_.scene().membrane.stiffness, (h0_ - c.lz()) / h0_, w.area);
    s[2] -= r.membrane_axial;
  }
  r.time = sim_.time();
  r.step = sim_.steps();
  r.axial_strain = (h0_ - c.lz()) / h0_;
  r.volumetric_strain = (v0_ - w.volume) / v0_;
  r.sigma_x = s[0];
  r.sigma_y = s[1];
  r.sigma_z = s[2];
  r.p = (s[0] + s[1] + s[2]) / 3;
  r.q = std::sqrt(0.5 * ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - s[2]) * (s[1] - s[2]) +
                         (s[2] - s[0]) * (s[2] - s[0])));
  r.friction_angle = mobilised_friction_angle(s[0], s[1], s[2]);
  r.void_ratio = w.volume / stats_.volume - 1;
  const Observables o = sim_.observe();
  r.coordination = o.particles > 0 ? o.contacts / o.particles : 0;
  r.kinetic_energy = o.kinetic();
  const Tensor3 lw = wrap ? love_weber_inside(sample, beads, w.volume)
                          : love_weber_slab(sample, sim_.scene().walls, c.z0, c.z1, w.area);
  r.lw_x = lw[0][0];
  r.lw_y = lw[1][1];
  r.lw_z = lw[2][2];
  const std::vector<WallReaction> now = sim_.wall_reactions();
  const int f = tri_.first_wall;
  double sx = 0, sy = 0;
  if (wrap) {
    sx = sy = sigma3_ + w.hoop_stress;
    r.coordination = inside_coordination(sample, beads);
    if (std::fabs(w.hoop_stress) > std::fabs(max_hoop_stress_)) max_hoop_stress_ = w.hoop_stress;
  } else {
    sx = (now[f + kTriX1].force[0] - now[f + kTriX0].force[0]) / (2 * c.ly() * c.lz());
    sy = (now[f + kTriY1].force[1] - now[f + kTriY0].force[1]) / (2 * c.lx() * c.lz());
  }
  const double sz = now[f + kTriPlaten].force[2] / w.area - r.membrane_axial;
  if (r.p > 0)
    r.lw_gap = std::max({std::fabs(r.lw_x - sx), std::fabs(r.lw_y - sy), std::fabs(r.lw_z - sz)}) / r.p;
  r.fabric_anisotropy = fabric_anisotropy(wrap ? beads_inside(sample, beads) : sample);
  r.inertial_number =
      r.p > 0 ? triaxial_inertial_number(rate_, stats_.diameter, stats_.density, r.p) : 0;
  last_sigma_z_ = s[2];
  rows_.push_back(r);
}

bool TriaxialProgramme::advance(std::int64_t max_steps) {
  if (!started_) {
    started_ = true;
    stage_start_ = sim_.steps();
    enter(tri_.settle_time > 0 ? Stage::Settle : Stage::Consolidate);
  }
  std::int64_t left = max_steps;
  while (left > 0 && stage_ != Stage::Done) {
    const std::int64_t event = stage_ != Stage::Compress ? next_check_
                               : follows_platen() ? std::min(next_row_, next_check_)
                                                  : next_row_;
    const std::int64_t n = std::min(left, event - sim_.steps());
    if (n > 0) sim_.advance(n);
    left -= std::max<std::int64_t>(n, 0);
    if (sim_.steps() < event) break;
    switch (stage_) {
      case Stage::Settle:
        if (settled_under_gravity(sim_, stats_, (sim_.steps() - stage_start_) * sim_.dt(),
                                  tri_.settle_time))
          enter(Stage::Consolidate);
        else next_check_ = sim_.steps() + check_every();
        return false;
      case Stage::Consolidate:
        if (consolidated()) enter(Stage::Compress);
        else next_check_ = sim_.steps() + check_every();
        return stage_ == Stage::Compress;
      case Stage::Compress:
        if (sim_.steps() < next_row_) {  // a check between rows: the sides follow the platen
          follow_platen();
          next_check_ = sim_.steps() + check_every();
          break;
        }
        measure_row();
        apply_servos(targets(last_sigma_z_), false);  // the sides, on their new areas
        next_row_ = sim_.steps() + row_steps_;
        if (static_cast<int>(rows_.size()) > tri_.rows) enter(Stage::Done);
        return true;
      case Stage::Done: break;
    }
  }
  return false;
}

TriaxialProgramme::StepCount TriaxialProgramme::step_count() const {
  const double dt = sim_.dt();
  const double in_stage = started_ ? double(sim_.steps() - stage_start_) : 0;
  const double settle = tri_.settle_time / dt * kSettleShare;
  const double consolidate = tri_.consolidate_time / dt * kConsolidateShare;
  const double compress = compress_steps_ > 0 ? double(compress_steps_)
                                              : tri_.axial_strain / (rate_ * dt);
  const double settled = settle_seconds_ / dt, consolidated = consolidate_seconds_ / dt;
  StepCount c;
  switch (stage_) {
    case Stage::Settle:
      c.done = in_stage;
      c.total = std::max(settle, in_stage) + consolidate + compress;
      break;
    case Stage::Consolidate:
      c.done = settled + in_stage;
      c.total = settled + std::max(consolidate, in_stage) + compress;
      break;
    case Stage::Compress:
      c.done = settled + consolidated + in_stage;
      c.total = settled + consolidated + std::max(compress, in_stage);
      break;
    case Stage::Done: c.done = c.total = settled + consolidated + compress; break;
  }
  return c;
}

std::string TriaxialProgramme::caption() const {
  char buf[200];
  if (rows_.empty()) {
    std::snprintf(buf, sizeof buf, "%s", stage_name());
  } else {
    const TriaxialRow& r = rows_.back();
    std::snprintf(buf, sizeof buf, "εₐ = %.2f %%, q/p′ = %.3f, φ′ = %.1f°", r.axial_strain * 100,
                  r.p > 0 ? r.q / r.p : 0, r.friction_angle);
  }
  return buf;
}

std::string TriaxialProgramme::status() const {
  char buf[200];
  if (stage_ == Stage::Compress && !rows_.empty()) {
    const TriaxialRow& r = rows_.back();
    std::snprintf(buf, sizeof buf, "compress eps_a = %.4f/%.3f, q/p = %.3f, phi = %.1f deg",
                  r.axial_strain, tri_.axial_strain, r.p > 0 ? r.q / r.p : 0, r.friction_angle);
  } else if (stage_ == Stage::Done) {
    std::snprintf(buf, sizeof buf, "done: %zu rows", rows_.size());
  } else {
    std::snprintf(buf, sizeof buf, "%s t = %.2f ms", stage_name(),
                  (sim_.steps() - stage_start_) * sim_.dt() * 1e3);
  }
  return buf;
}

TriaxialSummary TriaxialProgramme::summary() const {
  TriaxialSummary s;
  s.confining_stress = sigma3_;
  s.strain_rate = rate_;
  s.bead_diameter = stats_.diameter;
  s.settle_time = settle_seconds_;
  s.consolidate_time = consolidate_seconds_;
  s.membrane = membrane_;
  s.max_membrane_stress = max_hoop_stress_;
  analyse_triaxial_rows(rows_, s);
  return s;
}

std::string TriaxialProgramme::save_state() const {
  std::ostringstream o;
  o.precision(17);
  o << "triaxial_test 3\n"
    << started_ << ' ' << static_cast<int>(stage_) << ' ' << stage_start_ << ' ' << next_check_
    << ' ' << next_row_ << ' ' << row_steps_ << ' ' << compress_steps_ << ' ' << quiet_checks_
    << ' ' << rate_ << ' ' << h0_ << ' ' << v0_ << ' ' << last_sigma_z_ << ' ' << settle_seconds_
    << ' ' << consolidate_seconds_ << ' ' << sigma3_ << ' ' << hold_ << ' ' << max_hoop_stress_
    << ' ' << wrap_step_ << '\n'
    << rows_.size() << '\n';
  for (const TriaxialRow& r : rows_)
    o << r.time << ' ' << r.step << ' ' << r.axial_strain << ' ' << r.volumetric_strain << ' '
      << r.sigma_x << ' ' << r.sigma_y << ' ' << r.sigma_z << ' ' << r.p << ' ' << r.q << ' '
      << r.friction_angle << ' ' << r.void_ratio << ' ' << r.coordination << ' ' << r.lw_x << ' '
      << r.lw_y << ' ' << r.lw_z << ' ' << r.lw_gap << ' ' << r.fabric_anisotropy << ' ' << r.kinetic_energy << ' '
      << r.inertial_number << '\n';
  return o.str();
}

void TriaxialProgramme::restore_state(const std::string& text) {
  std::istringstream in(text);
  std::string tag;
  int version = 0, stage = 0;
  size_t count = 0;
  in >> tag >> version;
  if (tag != "triaxial_test" || version < 1 || version > 3)
    throw ReadError("the checkpoint holds no triaxial-test state");
  in >> started_ >> stage >> stage_start_ >> next_check_ >> next_row_ >> row_steps_ >>
      compress_steps_ >> quiet_checks_ >> rate_ >> h0_ >> v0_ >> last_sigma_z_ >>
      settle_seconds_ >> consolidate_seconds_;
  if (version >= 2) in >> sigma3_ >> hold_;  // version 1: the scene's, no hold
  if (version >= 3) in >> max_hoop_stress_ >> wrap_step_;
  in >> count;
  if (!in || stage < 0 || stage > 3 || count > 10000000)
    throw ReadError("malformed triaxial-test state");
  stage_ = static_cast<Stage>(stage);
  preparation_friction(sim_, tri_.specimen, started_ && stage_ == Stage::Settle);
  rows_.assign(count, {});
  for (TriaxialRow& r : rows_)
    in >> r.time >> r.step >> r.axial_strain >> r.volumetric_strain >> r.sigma_x >> r.sigma_y >>
        r.sigma_z >> r.p >> r.q >> r.friction_angle >> r.void_ratio >> r.coordination >> r.lw_x >>
        r.lw_y >> r.lw_z >> r.lw_gap >> r.fabric_anisotropy >> r.kinetic_energy >> r.inertial_number;
  if (!in) throw ReadError("malformed triaxial-test rows");
}

std::string TriaxialProgramme::rows_csv() const { return triaxial_rows_csv(rows_); }

std::string TriaxialProgramme::summary_text(double wall_seconds) const {
  TriaxialSummary s = summary();
  s.wall_seconds = wall_seconds;
  return triaxial_summary_text(s);
}

std::string TriaxialProgramme::describe() const {
  char buf[128];
  std::snprintf(buf, sizeof buf, "axial strain rate %.3g 1/s, %s", strain_rate(),
                membrane_ ? "a servo platen, the sides a membrane from the hand-over"
                          : "five servo plates");
  return buf;
}

}  // namespace simsols
