#include "solver/apparatus/oedometer/oedometer_programme.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "solver/apparatus/oedometer/oedometer.h"
#include "solver/apparatus/cell/stage_checks.h"
#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr double kCheckSeconds = 0.5e-3;
// Shares of the caps a step and the settling take before their end criteria
// hold (progress estimates only).
constexpr double kSettleShare = 0.3;
constexpr double kStepShare = 0.2;

const Oedometer& oedometer_of(const Simulation& sim) {
  const Oedometer* o = sim.scene().apparatus_as<Oedometer>();
  if (!o) throw std::invalid_argument("OedometerProgramme: the scene has no oedometer");
  return *o;
}

}  // namespace

OedometerProgramme::OedometerProgramme(Simulation& sim) : sim_(sim), oed_(oedometer_of(sim)) {
  stats_ = specimen_stats(sim.scene(), oed_.wall_material);
  servo_ = tune_platen_servo(stats_, oedometer_area(oed_), target(), sim.dt(), oed_.servo_gain,
                             oed_.servo_integral_time);
}

const char* OedometerProgramme::stage_name() const {
  switch (stage_) {
    case Stage::Settle: return "settle";
    case Stage::Load: return "load";
    case Stage::Done: return "done";
  }
  return "?";
}

double OedometerProgramme::height() {
  return sim_.wall_point(oed_.first_wall + kOedPlaten)[2] -
         sim_.wall_point(oed_.first_wall + kOedFloor)[2];
}

void OedometerProgramme::start_step(int index) {
  step_ = index;
  step_start_ = sim_.steps();
  quiet_checks_ = 0;
  servo_ = tune_platen_servo(stats_, oedometer_area(oed_), target(), sim_.dt(), oed_.servo_gain,
                             oed_.servo_integral_time);
  WallServo s;
  s.enabled = true;
  s.target_force = target() * oedometer_area(oed_);
  s.gain = servo_.gain;
  s.max_speed = oed_.servo_max_speed;
  s.integral_time = servo_.integral_time;
  sim_.set_servo(oed_.first_wall + kOedPlaten, s);
}

void OedometerProgramme::enter(Stage s) {
  const std::int64_t now = sim_.steps();
  if (stage_ == Stage::Settle) settle_seconds_ = (now - stage_start_) * sim_.dt();
  stage_ = s;
  stage_start_ = now;
  preparation_friction(sim_, oed_.specimen, s == Stage::Settle);
  next_check_ = now + std::max<std::int64_t>(50, std::llround(kCheckSeconds / sim_.dt()));
  const int platen = oed_.first_wall + kOedPlaten;
  if (s == Stage::Settle || s == Stage::Done) {
    WallServo off;
    sim_.set_servo(platen, off);
    sim_.set_wall_velocity(platen, {0, 0, 0});
    return;
  }
  lower_platen_onto_specimen(sim_, oed_.first_wall + kOedPlaten, 0.1 * stats_.diameter);
  sim_.read_wall_means();  // the first row's means start here
  start_step(0);
}

OedometerRow OedometerProgramme::measure_row(const Observables& o) {
  const auto means = sim_.read_wall_means();
  sim_.read_servo(oed_.first_wall + kOedPlaten);
  const int f = oed_.first_wall;
  const double L = oed_.length, W = oed_.width, A = L * W, H = height();
  OedometerRow r;
  r.time = sim_.time();
  r.step = sim_.steps();
  r.load_step = step_ + 1;
  r.sigma_target = target();
  r.sigma_top = means[f + kOedPlaten].force[2] / A;
  r.sigma_base = -means[f + kOedFloor].force[2] / A;
  const double fx = means[f + kOedX1].force[0] - means[f + kOedX0].force[0];
  const double fy = means[f + kOedY1].force[1] - means[f + kOedY0].force[1];
  r.sigma_hx = fx / (2 * W * H);
  r.sigma_hy = fy / (2 * L * H);
  r.sigma_h = (fx + fy) / (2 * (L + W) * H);
  r.height = H;
  r.void_ratio = A * H / stats_.volume - 1;
  const double sigma_v = 0.5 * (r.sigma_top + r.sigma_base);
  r.k0 = sigma_v > 0 ? r.sigma_h / sigma_v : 0;
  const double weight = stats_.mass * std::fabs(sim_.scene().effects.gravity[2]) / A;
  r.side_friction = r.sigma_top > 0 ? 1 - (r.sigma_base - weight) / r.sigma_top : 0;
  r.coordination = o.particles > 0 ? o.contacts / o.particles : 0;
  r.kinetic_energy = o.kinetic();
  return r;
}

// Equilibrium (oedometer_programme.h): the row's mean reaction on target, the
// beads and the platen at rest on the scale of a quasi-static deformation.
bool OedometerProgramme::quiet(const OedometerRow& row, const Observables& o) {
  const double sigma = target();
  const double scale = row.height / stats_.diameter * std::sqrt(sigma / stats_.density);
  const double v_rms = rms_bead_speed(o, stats_);
  const double v_platen = std::fabs(sim_.wall_velocity(oed_.first_wall + kOedPlaten)[2]);
  return std::fabs(row.sigma_top - sigma) < kOedometerForceError * sigma &&
         v_rms < kOedometerBeadsInertial * scale && v_platen < kOedometerPlatenInertial * scale;
}

bool OedometerProgramme::step_ended() {
  const Observables o = sim_.observe();
  OedometerRow row = measure_row(o);
  quiet_checks_ = quiet(row, o) ? quiet_checks_ + 1 : 0;
  const bool timed_out = (sim_.steps() - step_start_) * sim_.dt() >= oed_.step_time;
  if (quiet_checks_ >= 2) row.end_of_step = 1;
  else if (timed_out) row.end_of_step = 2;
  rows_.push_back(row);
  return row.end_of_step != 0;
}

bool OedometerProgramme::advance(std::int64_t max_steps) {
  if (!started_) {
    started_ = true;
    stage_start_ = sim_.steps();
    enter(oed_.settle_time > 0 ? Stage::Settle : Stage::Load);
  }
  const std::int64_t every = std::max<std::int64_t>(50, std::llround(kCheckSeconds / sim_.dt()));
  std::int64_t left = max_steps;
  while (left > 0 && stage_ != Stage::Done) {
    const std::int64_t n = std::min(left, next_check_ - sim_.steps());
    if (n > 0) sim_.advance(n);
    left -= std::max<std::int64_t>(n, 0);
    if (sim_.steps() < next_check_) break;
    next_check_ = sim_.steps() + every;
    if (stage_ == Stage::Settle) {
      const double elapsed = (sim_.steps() - stage_start_) * sim_.dt();
      if (settled_under_gravity(sim_, stats_, elapsed, oed_.settle_time)) enter(Stage::Load);
      return false;
    }
    if (step_ended()) {
      if (step_ + 1 < static_cast<int>(oed_.load_steps.size())) start_step(step_ + 1);
      else enter(Stage::Done);
    }
    return true;
  }
  return false;
}

OedometerProgramme::StepCount OedometerProgramme::step_count() const {
  const double dt = sim_.dt();
  const double settle = oed_.settle_time / dt * kSettleShare;
  const double per_step = oed_.step_time / dt * kStepShare;
  const double steps = static_cast<double>(oed_.load_steps.size());
  const double now = static_cast<double>(sim_.steps());
  StepCount c;
  c.done = now;
  switch (stage_) {
    case Stage::Settle: c.total = std::max(settle, now) + steps * per_step; break;
    case Stage::Load: {
      const double in_step = double(sim_.steps() - step_start_);
      c.total = now - in_step + std::max(per_step, in_step) + (steps - step_ - 1) * per_step;
      break;
    }
    case Stage::Done: c.total = now; break;
  }
  return c;
}

std::string OedometerProgramme::caption() const {
  char buf[200];
  if (rows_.empty()) {
    std::snprintf(buf, sizeof buf, "%s", stage_name());
  } else {
    const OedometerRow& r = rows_.back();
    std::snprintf(buf, sizeof buf, "σᵥ = %.1f kPa, e = %.4f, K₀ = %.3f", r.sigma_top * 1e-3,
                  r.void_ratio, r.k0);
  }
  return buf;
}

std::string OedometerProgramme::status() const {
  char buf[200];
  if (stage_ == Stage::Load && !rows_.empty()) {
    const OedometerRow& r = rows_.back();
    std::snprintf(buf, sizeof buf, "step %d/%zu: sigma_v = %.1f/%.0f kPa, e = %.4f, K0 = %.3f",
                  step_ + 1, oed_.load_steps.size(), r.sigma_top * 1e-3, target() * 1e-3,
                  r.void_ratio, r.k0);
  } else if (stage_ == Stage::Done) {
    std::snprintf(buf, sizeof buf, "done: %zu load steps", oed_.load_steps.size());
  } else {
    std::snprintf(buf, sizeof buf, "%s t = %.2f ms", stage_name(),
                  (sim_.steps() - stage_start_) * sim_.dt() * 1e3);
  }
  return buf;
}

OedometerSummary OedometerProgramme::summary() const {
  OedometerSummary s = analyse_oedometer(rows_, oedometer_peak_step(oed_), oed_.friction_angle);
  s.bead_diameter = stats_.diameter;
  s.settle_time = settle_seconds_;
  return s;
}

std::string OedometerProgramme::save_state() const {
  std::ostringstream o;
  o.precision(17);
  o << "oedometer_test 1\n"
    << started_ << ' ' << static_cast<int>(stage_) << ' ' << step_ << ' ' << stage_start_ << ' '
    << step_start_ << ' ' << next_check_ << ' ' << quiet_checks_ << ' ' << settle_seconds_ << ' '
    << servo_.gain << ' ' << servo_.integral_time << '\n'
    << rows_.size() << '\n';
  for (const OedometerRow& r : rows_)
    o << r.time << ' ' << r.step << ' ' << r.load_step << ' ' << r.sigma_target << ' '
      << r.sigma_top << ' ' << r.sigma_base << ' ' << r.sigma_hx << ' ' << r.sigma_hy << ' '
      << r.sigma_h << ' ' << r.height << ' ' << r.void_ratio << ' ' << r.k0 << ' '
      << r.side_friction << ' ' << r.coordination << ' ' << r.kinetic_energy << ' '
      << r.end_of_step << '\n';
  return o.str();
}

void OedometerProgramme::restore_state(const std::string& text) {
  std::istringstream in(text);
  std::string tag;
  int version = 0, stage = 0;
  size_t count = 0;
  in >> tag >> version;
  if (tag != "oedometer_test" || version != 1)
    throw ReadError("the checkpoint holds no oedometer-test state");
  in >> started_ >> stage >> step_ >> stage_start_ >> step_start_ >> next_check_ >>
      quiet_checks_ >> settle_seconds_ >> servo_.gain >> servo_.integral_time >> count;
  if (!in || stage < 0 || stage > 2 || step_ < 0 ||
      step_ >= static_cast<int>(oed_.load_steps.size()))
    throw ReadError("malformed oedometer-test state");
  stage_ = static_cast<Stage>(stage);
  preparation_friction(sim_, oed_.specimen, started_ && stage_ == Stage::Settle);
  if (count > 10000000) throw ReadError("malformed oedometer-test state");
  rows_.assign(count, {});
  for (OedometerRow& r : rows_)
    in >> r.time >> r.step >> r.load_step >> r.sigma_target >> r.sigma_top >> r.sigma_base >>
        r.sigma_hx >> r.sigma_hy >> r.sigma_h >> r.height >> r.void_ratio >> r.k0 >>
        r.side_friction >> r.coordination >> r.kinetic_energy >> r.end_of_step;
  if (!in) throw ReadError("malformed oedometer-test rows");
}

std::string OedometerProgramme::rows_csv() const { return oedometer_rows_csv(rows_); }

std::string OedometerProgramme::summary_text(double wall_seconds) const {
  OedometerSummary s = summary();
  s.wall_seconds = wall_seconds;
  return oedometer_summary_text(s);
}

std::string OedometerProgramme::describe() const {
  char buf[128];
  std::snprintf(buf, sizeof buf, "servo gain %.3g m/(s N), integral time %.3g s (first step)",
                servo_gain(), servo_integral_time());
  return buf;
}

}  // namespace simsols
