#include "shear_test.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "contact_model.h"
#include "shear_box.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRad = 180.0 / kPi;

// Servo tuning (see docs/shear-box.md): the proportional gain makes the
// platen's contacts relax in ~1/kGainFraction steps; the integral removes the
// steady error while the specimen dilates, over kIntegralPeriods of the
// specimen's vertical oscillation period.
constexpr double kGainFraction = 0.5;
constexpr double kIntegralPeriods = 5.0;

// Shares of the settle and consolidate caps the paper's tests take before
// their end criteria hold (for progress estimates only).
constexpr double kSettleShare = 0.3;
constexpr double kConsolidateShare = 0.3;

// A first peak is a maximum of mobilised strength: while the running
// maximum of tau/sigma is below this share of the test's largest, its
// wiggles (noise about zero at the start of shearing) are not softening.
constexpr double kPeakMobilised = 0.25;

const ShearBox& box_of(const Simulation& sim) {
  if (!sim.scene().shear_box) throw std::invalid_argument("ShearTest: the scene has no shear box");
  return *sim.scene().shear_box;
}

// Slope of y(x) by least squares over rows [a, b).
double slope(const std::vector<ShearRow>& r, size_t a, size_t b) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(b - a);
  for (size_t i = a; i < b; ++i) {
    sx += r[i].displacement;
    sy += r[i].dilation;
    sxx += r[i].displacement * r[i].displacement;
    sxy += r[i].displacement * r[i].dilation;
  }
  const double den = n * sxx - sx * sx;
  return den > 0 ? (n * sxy - sx * sy) / den : 0;
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

ShearTest::ShearTest(Simulation& sim) : sim_(sim), box_(box_of(sim)) {
  const Scene& scene = sim.scene();
  double d = 0, mass = 0;
  for (const Particle& p : scene.particles) {
    d += 2 * p.radius;
    mass += scene.materials[p.material].density * 4.0 / 3.0 * kPi * std::pow(p.radius, 3);
  }
  const double n = static_cast<double>(scene.particles.size());
  diameter_ = d / n;
  bead_mass_ = mass / n;
  density_ = scene.materials[scene.particles[0].material].density;
  sigma_target_ = box_.normal_stress;

  const PairTable pairs = make_pair_table(scene);
  const double e_star = pairs.at(scene.particles[0].material, box_.wall_material).e_star;
  k_hertz_ = 4.0 / 3.0 * e_star * std::sqrt(diameter_ / 2);
  specimen_mass_ = mass;
  double top = 0;
  for (const Particle& p : scene.particles) top = std::max(top, p.position[2] + p.radius);
  layers_ = std::max(1.0, top / diameter_);
  tune_servo();
}

// Automatic servo settings from the Hertz stiffness of the platen's
// contacts at the target stress, one bead per d^2 of platen. Retuned when
// the target changes: the contacts stiffen as sigma^(1/3), so a gain tuned
// at 50 kPa is twice as sharp at 400 kPa, at the limit of the loop's
// stability (docs/shear-box.md), and the platen rang from step to step
// (stability case 6).
void ShearTest::tune_servo() {
  const double contacts = shear_area(box_) / (diameter_ * diameter_);
  const double f_contact = sigma_target_ * diameter_ * diameter_;
  const double k_contact = 1.5 * std::cbrt(f_contact) * std::pow(k_hertz_, 2.0 / 3.0);
  const double k_platen = contacts * k_contact;
  gain_ = box_.servo_gain > 0 ? box_.servo_gain : kGainFraction / (k_platen * sim_.dt());
  const double period = 2 * kPi * std::sqrt(specimen_mass_ / (k_platen / layers_));
  integral_time_ = box_.servo_integral_time > 0 ? box_.servo_integral_time
                                                : kIntegralPeriods * period;
}

double ShearTest::shear_speed_for(double height) const {
  if (speed_override_ > 0) return speed_override_;
  return box_.shear_speed > 0 ? box_.shear_speed
                              : speed_for_inertial_number(box_.inertial_number, height,
                                                          diameter_, density_, sigma_target_);
}

double ShearTest::inertial_number() const {
  return height0_ > 0 ? inertial_number_of(speed_, height0_, diameter_, density_, sigma_target_)
                      : 0;
}

std::int64_t ShearTest::steps_for(double seconds) const {
  return std::max<std::int64_t>(1, std::llround(seconds / sim_.dt()));
}

void ShearTest::apply_servo(bool on) {
  WallServo s;
  s.enabled = on;
  s.target_force = sigma_target_ * shear_area(box_);
  s.gain = gain_;
  s.max_speed = box_.servo_max_speed;
  s.integral_time = integral_time_;
  sim_.set_servo(box_.first_wall + kPlaten, s);
}

void ShearTest::set_normal_stress(double pascals) {
  if (!(pascals > 0) || !std::isfinite(pascals))
    throw std::invalid_argument("normal stress must be > 0 Pa");
  sigma_target_ = pascals;
  tune_servo();
  if (phase_ == ShearPhase::Consolidate || phase_ == ShearPhase::Shear) apply_servo(true);
}

void ShearTest::start_shear() {
  hold_ = false;
  if (ready_to_shear()) enter(ShearPhase::Shear);
}

void ShearTest::set_shear_speed(double v) {
  if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument("shear speed must be > 0 m/s");
  speed_override_ = v;
  if (phase_ != ShearPhase::Shear) return;
  speed_ = v;
  move_lower_half(v);
  const double done = rows_.empty() ? 0 : rows_.back().displacement;
  const int left = std::max(1, box_.rows - static_cast<int>(rows_.size()));
  const double remaining = std::max(0.0, box_.shear_displacement - done);
  row_steps_ = std::max<std::int64_t>(1, std::llround(remaining / (v * sim_.dt()) / left));
  next_row_ = sim_.steps() + row_steps_;
}

void ShearTest::move_lower_half(double vx) {
  for (int w = kFloor; w <= kLowerLast; ++w) sim_.set_wall_velocity(box_.first_wall + w, {vx, 0, 0});
}

void ShearTest::enter(ShearPhase p) {
  const std::int64_t now = sim_.steps();
  const double elapsed = (now - phase_start_) * sim_.dt();
  if (phase_ == ShearPhase::Settle) settle_seconds_ = elapsed;
  if (phase_ == ShearPhase::Consolidate) consolidate_seconds_ = elapsed;
  phase_ = p;
  phase_start_ = now;
  quiet_checks_ = 0;
  next_check_ = now + std::max<std::int64_t>(50, steps_for(0.5e-3));
  switch (p) {
    case ShearPhase::Settle:
      apply_servo(false);
      break;
    case ShearPhase::Consolidate: {
      // The platen is lowered onto the settled specimen (a tenth of a
      // diameter above its highest bead) and its servo switched on.
      const ParticleSnapshot snap = sim_.snapshot();
      double top = 0;
      for (size_t i = 0; i < snap.position.size(); ++i)
        top = std::max(top, snap.position[i][2] + snap.radius[i]);
      Vec3 p = sim_.wall_point(box_.first_wall + kPlaten);
      p[2] = std::min(p[2], top + 0.1 * diameter_);
      sim_.set_wall_point(box_.first_wall + kPlaten, p);
      sim_.read_servo(box_.first_wall + kPlaten);
      apply_servo(true);
      break;
    }
    case ShearPhase::Shear: {
      x0_ = sim_.wall_point(box_.first_wall + kFloor)[0];
      z0_ = sim_.wall_point(box_.first_wall + kPlaten)[2];
      height0_ = z0_ - sim_.wall_point(box_.first_wall + kFloor)[2];
      speed_ = shear_speed_for(height0_);
      shear_steps_ = std::max<std::int64_t>(
          box_.rows, std::llround(box_.shear_displacement / (speed_ * sim_.dt())));
      row_steps_ = std::max<std::int64_t>(1, shear_steps_ / box_.rows);
      shear_steps_ = row_steps_ * box_.rows;
      move_lower_half(speed_);
      sim_.read_wall_means();
      sim_.read_servo(box_.first_wall + kPlaten);
      next_row_ = now + row_steps_;
      break;
    }
    case ShearPhase::Done:
      move_lower_half(0);
      apply_servo(false);
      break;
  }
}

bool ShearTest::settled() {
  const std::int64_t now = sim_.steps();
  const double elapsed = (now - phase_start_) * sim_.dt();
  if (elapsed >= box_.settle_time) return true;
  const bool gravity = sim_.scene().has_gravity();
  if (gravity && elapsed < 2e-3) return false;
  const Observables o = sim_.observe();
  const double scale = o.particles * bead_mass_ * 9.81 * diameter_;
  return o.kinetic() < 1e-4 * scale;
}

bool ShearTest::consolidated() {
  const std::int64_t now = sim_.steps();
  const double elapsed = (now - phase_start_) * sim_.dt();
  if (elapsed >= box_.consolidate_time) return true;
  const double target = sigma_target_ * shear_area(box_);
  const Simulation::ServoReading r = sim_.read_servo(box_.first_wall + kPlaten);
  const Observables o = sim_.observe();
  const double v_rms = std::sqrt(2 * o.kinetic_translational / (o.particles * bead_mass_));
  const double height = sim_.wall_point(box_.first_wall + kPlaten)[2];
  const double v_shear = shear_speed_for(height);
  const bool quiet = std::fabs(r.mean - target) < 0.01 * target && v_rms < 0.1 * v_shear;
  quiet_checks_ = quiet ? quiet_checks_ + 1 : 0;
  return quiet_checks_ >= 2;
}

void ShearTest::measure_row() {
  const auto means = sim_.read_wall_means();
  sim_.read_servo(box_.first_wall + kPlaten);
  const int f = box_.first_wall;
  ShearRow row;
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
  row.dilation = platen[2] - z0_;
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

bool ShearTest::advance(std::int64_t max_steps) {
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
        if (static_cast<int>(rows_.size()) >= box_.rows) enter(ShearPhase::Done);
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
ShearTest::StepCount ShearTest::step_count() const {
  const double dt = sim_.dt();
  const double elapsed = started_ ? double(sim_.steps() - phase_start_) : 0;
  const double settle = box_.settle_time / dt * kSettleShare;
  const double consolidate = box_.consolidate_time / dt * kConsolidateShare;
  const double shear = shear_steps_ > 0 ? double(shear_steps_)
                                        : box_.shear_displacement /
                                              (shear_speed_for(layers_ * diameter_) * dt);
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

double ShearTest::progress() const {
  const StepCount c = step_count();
  return c.total > 0 ? std::min(1.0, c.done / c.total) : 0;
}

std::string ShearTest::status() const {
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

ShearSummary ShearTest::summary() const {
  ShearSummary s;
  s.normal_stress_target = sigma_target_;
  s.shear_speed = speed_;
  s.specimen_height = height0_;
  s.bead_diameter = diameter_;
  s.settle_time = settle_seconds_;
  s.consolidate_time = consolidate_seconds_;
  analyse_shear_rows(rows_, s);
  return s;
}

std::string ShearTest::save_state() const {
  std::ostringstream o;
  o.precision(17);
  o << "shear_test 2\n"
    << started_ << ' ' << static_cast<int>(phase_) << ' ' << phase_start_ << ' ' << next_check_
    << ' ' << next_row_ << ' ' << row_steps_ << ' ' << shear_steps_ << ' ' << quiet_checks_
    << '\n'
    << sigma_target_ << ' ' << speed_ << ' ' << gain_ << ' ' << integral_time_ << ' ' << x0_
    << ' ' << z0_ << ' ' << height0_ << ' ' << settle_seconds_ << ' ' << consolidate_seconds_
    << '\n'
    << hold_ << ' ' << ready_ << ' ' << speed_override_ << '\n'
    << rows_.size() << '\n';
  for (const ShearRow& r : rows_)
    o << r.time << ' ' << r.step << ' ' << r.displacement << ' ' << r.shear_force << ' '
      << r.shear_force_upper << ' ' << r.tau << ' ' << r.tau_corrected << ' ' << r.normal_force
      << ' ' << r.sigma << ' ' << r.dilation << ' ' << r.friction_angle << ' ' << r.coordination
      << ' ' << r.kinetic_energy << ' ' << r.inertial_number << ' ' << r.outside << '\n';
  return o.str();
}

void ShearTest::restore_state(const std::string& text) {
  std::istringstream in(text);
  std::string tag;
  int version = 0, phase = 0;
  size_t count = 0;
  in >> tag >> version;
  if (tag != "shear_test" || (version != 1 && version != 2))
    throw std::runtime_error("the checkpoint holds no shear-test state");
  in >> started_ >> phase >> phase_start_ >> next_check_ >> next_row_ >> row_steps_ >>
      shear_steps_ >> quiet_checks_ >> sigma_target_ >> speed_ >> gain_ >> integral_time_ >>
      x0_ >> z0_ >> height0_ >> settle_seconds_ >> consolidate_seconds_;
  hold_ = ready_ = false;
  speed_override_ = 0;
  if (version == 2) in >> hold_ >> ready_ >> speed_override_;  // version 1: no bench control
  in >> count;
  if (!in || phase < 0 || phase > 3) throw std::runtime_error("malformed shear-test state");
  phase_ = static_cast<ShearPhase>(phase);
  rows_.assign(count, {});
  for (ShearRow& r : rows_)
    in >> r.time >> r.step >> r.displacement >> r.shear_force >> r.shear_force_upper >> r.tau >>
        r.tau_corrected >> r.normal_force >> r.sigma >> r.dilation >> r.friction_angle >>
        r.coordination >> r.kinetic_energy >> r.inertial_number >> r.outside;
  if (!in) throw std::runtime_error("malformed shear-test rows");
}

std::string shear_rows_csv(const std::vector<ShearRow>& rows) {
  std::string out =
      "time_s,step,displacement_mm,shear_force_N,shear_force_upper_N,tau_kPa,tau_corrected_kPa,"
      "normal_force_N,sigma_kPa,dilation_mm,tau_over_sigma,friction_angle_deg,coordination,"
      "kinetic_energy_J,inertial_number,outside\n";
  char buf[512];
  for (const ShearRow& r : rows) {
    std::snprintf(buf, sizeof buf,
                  "%.9g,%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n",
                  r.time, static_cast<long long>(r.step), r.displacement * 1e3, r.shear_force,
                  r.shear_force_upper, r.tau * 1e-3, r.tau_corrected * 1e-3, r.normal_force,
                  r.sigma * 1e-3, r.dilation * 1e3, r.sigma > 0 ? r.tau / r.sigma : 0,
                  r.friction_angle, r.coordination, r.kinetic_energy, r.inertial_number,
                  r.outside);
    out += buf;
  }
  return out;
}

Residual residual_of(const std::vector<ShearRow>& rows, double sigma_target) {
  Residual r;
  if (rows.empty()) return r;
  // the window's first row sits at 0.8 x the end when rows are evenly
  // spaced: included whether the displacements are exact or read back from
  // shear.csv (9 digits)
  const double from = 0.8 * rows.back().displacement * (1 - 1e-7);
  int count = 0;
  for (const ShearRow& row : rows)
    if (row.displacement >= from && row.sigma > 0.5 * sigma_target) {
      r.tau += row.tau;
      r.ratio += row.tau / row.sigma;
      ++count;
    }
  if (count > 0) {
    r.tau /= count;
    r.ratio /= count;
  }
  return r;
}

FirstPeak first_peak(const std::vector<ShearRow>& rows, double sigma_target, double softening) {
  // what counts as a peak: a quarter of the test's largest ratio, and no
  // less than its residual strength
  double top = 0;
  for (const ShearRow& r : rows)
    if (r.sigma > 0.5 * sigma_target) top = std::max(top, r.tau / r.sigma);
  const double floor = std::max(kPeakMobilised * top, residual_of(rows, sigma_target).ratio);
  FirstPeak best;
  for (const ShearRow& r : rows) {
    if (!(r.sigma > 0.5 * sigma_target)) continue;
    const double ratio = r.tau / r.sigma;
    if (ratio > best.ratio) {
      best.ratio = ratio;
      best.displacement = r.displacement;
      best.row = static_cast<int>(&r - rows.data());
    } else if (best.ratio >= floor && ratio < (1 - softening) * best.ratio) {
      break;  // softened: the running maximum was the first peak
    }
  }
  return best;
}

void analyse_shear_rows(const std::vector<ShearRow>& rows, ShearSummary& out) {
  // the apparatus' fields are kept; the rest is derived afresh
  ShearSummary s;
  s.normal_stress_target = out.normal_stress_target;
  s.shear_speed = out.shear_speed;
  s.specimen_height = out.specimen_height;
  s.bead_diameter = out.bead_diameter;
  s.settle_time = out.settle_time;
  s.consolidate_time = out.consolidate_time;
  s.wall_seconds = out.wall_seconds;
  out = s;
  if (rows.empty()) return;
  const double target = s.normal_stress_target;
  s.sigma_min = s.sigma_max = rows[0].sigma;
  for (const ShearRow& r : rows) {
    // a platen that lost contact (sigma far below target) gives no ratio
    const double ratio = r.sigma > 0.5 * target ? r.tau / r.sigma : 0;
    if (ratio > s.max_ratio) {
      s.max_ratio = ratio;
      s.max_displacement = r.displacement;
    }
    s.max_tau = std::max(s.max_tau, r.tau);
    s.max_inertial_number = std::max(s.max_inertial_number, r.inertial_number);
    s.sigma_min = std::min(s.sigma_min, r.sigma);
    s.sigma_max = std::max(s.sigma_max, r.sigma);
    s.max_outside = std::max(s.max_outside, r.outside);
  }
  s.max_angle = std::atan(s.max_ratio) * kRad;
  const FirstPeak first = first_peak(rows, target);
  s.peak_ratio = first.ratio;
  s.peak_displacement = first.displacement;
  s.peak_angle = std::atan(first.ratio) * kRad;
  s.peak_tau = first.row >= 0 ? rows[first.row].tau : 0;
  const Residual res = residual_of(rows, target);
  s.residual_tau = res.tau;
  s.residual_ratio = res.ratio;
  s.residual_angle = std::atan(res.ratio) * kRad;
  // Dilatancy: least-squares slope of dz(dx) over a sliding window of
  // ~1/40 of the test (at least 3 rows), the steepest rise.
  const size_t w = std::max<size_t>(3, rows.size() / 40);
  double steepest = 0;
  for (size_t a = 0; a + w <= rows.size(); ++a) steepest = std::max(steepest, slope(rows, a, a + w));
  s.max_dilatancy_angle = std::atan(steepest) * kRad;
  out = s;
}

std::string shear_summary_text(const ShearSummary& s) {
  char buf[2048];
  std::snprintf(
      buf, sizeof buf,
      "normal_stress_kPa = %.6g\nbead_diameter_mm = %.6g\nspecimen_height_mm = %.6g\n"
      "shear_speed_mm_s = %.6g\npeak_tau_kPa = %.6g\npeak_tau_over_sigma = %.6g\n"
      "peak_friction_angle_deg = %.4f\npeak_displacement_mm = %.6g\n"
      "max_tau_kPa = %.6g\nmax_tau_over_sigma = %.6g\nmax_friction_angle_deg = %.4f\n"
      "max_displacement_mm = %.6g\nresidual_tau_kPa = %.6g\n"
      "residual_tau_over_sigma = %.6g\nresidual_friction_angle_deg = %.4f\n"
      "max_dilatancy_angle_deg = %.4f\nmax_inertial_number = %.4g\nsigma_min_kPa = %.6g\n"
      "sigma_max_kPa = %.6g\nsigma_band_percent = %+.3f %+.3f\nmax_beads_outside = %d\n"
      "settle_time_s = %.6g\nconsolidate_time_s = %.6g\nwall_seconds = %.1f\n",
      s.normal_stress_target * 1e-3, s.bead_diameter * 1e3, s.specimen_height * 1e3,
      s.shear_speed * 1e3, s.peak_tau * 1e-3, s.peak_ratio, s.peak_angle,
      s.peak_displacement * 1e3, s.max_tau * 1e-3, s.max_ratio, s.max_angle,
      s.max_displacement * 1e3, s.residual_tau * 1e-3, s.residual_ratio, s.residual_angle,
      s.max_dilatancy_angle, s.max_inertial_number, s.sigma_min * 1e-3, s.sigma_max * 1e-3,
      100 * (s.sigma_min / s.normal_stress_target - 1),
      100 * (s.sigma_max / s.normal_stress_target - 1), s.max_outside, s.settle_time,
      s.consolidate_time, s.wall_seconds);
  return buf;
}

}  // namespace simsols

namespace simsols {
namespace {

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

double to_double(const std::string& s, const std::string& what) {
  try {
    size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == 0) throw std::invalid_argument(s);
    return v;
  } catch (const std::exception&) {
    throw std::runtime_error("malformed number '" + s + "' in " + what);
  }
}

}  // namespace

std::vector<ShearRow> parse_shear_rows_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  if (line.rfind("time_s,step,displacement_mm", 0) != 0)
    throw std::runtime_error("not a shear.csv (header differs)");
  std::vector<ShearRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto f = split(line, ',');
    if (f.size() != 16)
      throw std::runtime_error("shear.csv row " + std::to_string(rows.size() + 1) + " has " +
                               std::to_string(f.size()) + " fields, expected 16");
    const std::string where = "shear.csv row " + std::to_string(rows.size() + 1);
    std::vector<double> v;
    for (const std::string& x : f) v.push_back(to_double(x, where));
    ShearRow r;
    r.time = v[0];
    r.step = static_cast<std::int64_t>(v[1]);
    r.displacement = v[2] * 1e-3;
    r.shear_force = v[3];
    r.shear_force_upper = v[4];
    r.tau = v[5] * 1e3;
    r.tau_corrected = v[6] * 1e3;
    r.normal_force = v[7];
    r.sigma = v[8] * 1e3;
    r.dilation = v[9] * 1e-3;
    r.friction_angle = v[11];
    r.coordination = v[12];
    r.kinetic_energy = v[13];
    r.inertial_number = v[14];
    r.outside = static_cast<int>(v[15]);
    rows.push_back(r);
  }
  return rows;
}

namespace {

// Summaries written before the peak meant the first peak called the overall
// maximum peak_* and the first peak first_peak_*: their keys, renamed.
void rename_older_keys(std::map<std::string, std::string>& kv) {
  if (!kv.count("first_peak_tau_over_sigma")) return;
  for (const char* k : {"tau_kPa", "tau_over_sigma", "friction_angle_deg", "displacement_mm"}) {
    const std::string peak = std::string("peak_") + k, first = "first_" + peak;
    if (kv.count(peak)) kv["max_" + std::string(k)] = kv[peak];
    kv.erase(peak);
    if (kv.count(first)) kv[peak] = kv[first];
  }
}

}  // namespace

ShearSummary parse_shear_summary(const std::string& text) {
  std::map<std::string, std::string> kv;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const size_t eq = line.find(" = ");
    if (eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 3);
  }
  rename_older_keys(kv);
  ShearSummary s;
  const struct {
    const char* key;
    double* target;
    double scale;
  } fields[] = {{"normal_stress_kPa", &s.normal_stress_target, 1e3},
                {"bead_diameter_mm", &s.bead_diameter, 1e-3},
                {"specimen_height_mm", &s.specimen_height, 1e-3},
                {"shear_speed_mm_s", &s.shear_speed, 1e-3},
                {"peak_tau_kPa", &s.peak_tau, 1e3},
                {"peak_tau_over_sigma", &s.peak_ratio, 1},
                {"peak_friction_angle_deg", &s.peak_angle, 1},
                {"peak_displacement_mm", &s.peak_displacement, 1e-3},
                {"max_tau_kPa", &s.max_tau, 1e3},
                {"max_tau_over_sigma", &s.max_ratio, 1},
                {"max_friction_angle_deg", &s.max_angle, 1},
                {"max_displacement_mm", &s.max_displacement, 1e-3},
                {"residual_tau_kPa", &s.residual_tau, 1e3},
                {"residual_tau_over_sigma", &s.residual_ratio, 1},
                {"residual_friction_angle_deg", &s.residual_angle, 1},
                {"max_dilatancy_angle_deg", &s.max_dilatancy_angle, 1},
                {"max_inertial_number", &s.max_inertial_number, 1},
                {"sigma_min_kPa", &s.sigma_min, 1e3},
                {"sigma_max_kPa", &s.sigma_max, 1e3},
                {"settle_time_s", &s.settle_time, 1},
                {"consolidate_time_s", &s.consolidate_time, 1},
                {"wall_seconds", &s.wall_seconds, 1}};
  int seen = 0;
  for (const auto& f : fields)
    if (const auto it = kv.find(f.key); it != kv.end()) {
      *f.target = to_double(it->second, "summary key " + it->first) * f.scale;
      ++seen;
    }
  if (const auto it = kv.find("max_beads_outside"); it != kv.end())
    s.max_outside = static_cast<int>(to_double(it->second, it->first));
  if (seen < 10) throw std::runtime_error("not a shear-test summary (too few keys)");
  return s;
}

MohrCoulomb fit_mohr_coulomb(const std::vector<double>& sigma, const std::vector<double>& tau) {
  MohrCoulomb m;
  const size_t n = std::min(sigma.size(), tau.size());
  m.points = static_cast<int>(n);
  if (n < 2) return m;
  double sx = 0, sy = 0;
  for (size_t i = 0; i < n; ++i) {
    sx += sigma[i];
    sy += tau[i];
  }
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0, ss_tot = 0;
  for (size_t i = 0; i < n; ++i) {
    sxx += (sigma[i] - mx) * (sigma[i] - mx);
    sxy += (sigma[i] - mx) * (tau[i] - my);
    ss_tot += (tau[i] - my) * (tau[i] - my);
  }
  if (sxx <= 0) return m;
  m.tan_phi = sxy / sxx;
  m.cohesion = my - m.tan_phi * mx;
  m.phi_deg = std::atan(m.tan_phi) * kRad;
  double ss_res = 0;
  for (size_t i = 0; i < n; ++i) {
    const double e = tau[i] - (m.cohesion + m.tan_phi * sigma[i]);
    ss_res += e * e;
  }
  m.r2 = ss_tot > 0 ? 1 - ss_res / ss_tot : 1;
  m.exact = n == 2;
  if (m.exact) {
    m.cohesion_se = m.tan_phi_se = m.phi_se_deg = std::numeric_limits<double>::quiet_NaN();
    return m;
  }
  const double s2 = ss_res / double(n - 2);
  m.tan_phi_se = std::sqrt(s2 / sxx);
  m.cohesion_se = std::sqrt(s2 * (1.0 / n + mx * mx / sxx));
  m.phi_se_deg = m.tan_phi_se / (1 + m.tan_phi * m.tan_phi) * kRad;
  return m;
}

}  // namespace simsols
