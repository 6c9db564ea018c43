#include "solver/apparatus/periodic_cell/cell_programme.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "solver/common/errors.h"

namespace simsols {
namespace {

constexpr double kBeta = 1;               // the servo's share of an error corrected per control, at most
constexpr double kStressTolerance = 0.01;  // compressed: every normal stress within 1 %
constexpr double kQuietInertial = 1e-4;    // compressed: rattling below this inertial number
constexpr int kQuietControls = 10;         // ... for this many controls in a row
constexpr int kCompressRowControls = 25;   // a compression row every so many controls
constexpr double kIntegralControls = 10;   // the servo's integral time, in controls

const PeriodicCell& cell_of(const Simulation& sim) {
  const PeriodicCell* c = sim.scene().apparatus_as<PeriodicCell>();
  if (!c) throw std::invalid_argument("CellProgramme: the scene has no periodic cell");
  return *c;
}

// q = sqrt(3 J2) of a stress tensor (Pa).
double deviator(const Mat3& s) {
  const double p = (s[0] + s[4] + s[8]) / 3;
  double j2 = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double d = s[3 * a + b] - (a == b ? p : 0);
      j2 += 0.5 * d * d;
    }
  return std::sqrt(3 * j2);
}

}  // namespace

CellProgramme::CellProgramme(Simulation& sim) : sim_(sim), cell_(cell_of(sim)) {
  const Material& m = sim.scene().materials.at(cell_.material);
  diameter_ = cell_.diameter;
  density_ = m.density;
  e_star_ = m.young_modulus / (2 * (1 - m.poisson_ratio * m.poisson_ratio));
  volume0_ = det3(sim.state().cell_now.h);
  apply_friction();
}

// The preparation friction and restitution while compressing (a gas of
// nearly elastic grains would not cool while the servo works on it), the
// materials' own after.
void CellProgramme::apply_friction() {
  if (stage_ == Stage::Compress)
    sim_.override_friction(
        Model::FrictionOverride{cell_.preparation_friction, cell_.preparation_rolling_friction,
                                cell_.preparation_restitution});
  else
    sim_.override_friction(std::nullopt);
}

const char* CellProgramme::stage_name() const {
  switch (stage_) {
    case Stage::Compress: return "compress";
    case Stage::Test: return "test";
    case Stage::Done: return "done";
  }
  return "?";
}

double CellProgramme::test_rate() const {
  return cell_.inertial_number * std::sqrt(cell_.pressure / density_) / diameter_;
}

double CellProgramme::servo_rate_max() const {
  return cell_.compression_inertial_number * std::sqrt(cell_.pressure / density_) / diameter_;
}

double CellProgramme::end_strain() const {
  if (oedometric()) return kOedometricTravelEstimate;  // its end is a stress
  return cell_.test == PeriodicCell::Test::SimpleShear ? cell_.shear_strain : cell_.axial_strain;
}

// The affine (Voigt) stiffness of a Hertz packing at its mean contact force
// under an isotropic strain, 3 K = phi Z k_n / (2 pi R), k_n = 2 E* sqrt(R*
// delta): an upper bound of what any normal stress answers to its strain
// (one axis strained alone: 3 phi Z k_n / (10 pi R) from the normal springs;
// the packing's non-affine motion softens both).
double CellProgramme::stiffness(const CellMeasure& m) const {
  const double r = 0.5 * diameter_, p = m.pressure(), z = m.coordination;
  if (!(p > 0) || z < 1) return 0;
  const double force = 4 * std::numbers::pi * r * r * p / (z * m.solid_fraction);
  const double r_star = 0.5 * r;
  const double delta = std::pow(3 * force / (4 * e_star_ * std::sqrt(r_star)), 2.0 / 3.0);
  const double k_n = 2 * e_star_ * std::sqrt(r_star * delta);
  return m.solid_fraction * z * k_n / (2 * std::numbers::pi * r);
}

double CellProgramme::target(int axis, const CellMeasure& m) const {
  if (stage_ == Stage::Test && cell_.test == PeriodicCell::Test::AxialCompression &&
      cell_.path == PeriodicCell::Path::ConstantP && axis < 2)
    return std::max(0.0, 0.5 * (3 * cell_.pressure - m.stress[8]));
  return cell_.pressure;
}

void CellProgramme::servo(const CellMeasure& m, Mat3& grad) {
  const double rate_max = servo_rate_max();
  const double dt_c = kControlSteps * sim_.dt();
  const double stiff = stiffness(m);
  bool controlled[3] = {true, true, true};
  if (stage_ == Stage::Test && cell_.test == PeriodicCell::Test::SimpleShear)
    controlled[0] = controlled[1] = false;
  if (stage_ == Stage::Test && cell_.test == PeriodicCell::Test::AxialCompression) controlled[2] = false;
  if (stage_ == Stage::Test && oedometric()) controlled[0] = controlled[1] = controlled[2] = false;
  for (int a = 0; a < 3; ++a) {
    if (!controlled[a]) {
      integral_[a] = 0;
      continue;
    }
    const double err = m.stress[4 * a] - target(a, m);
    if (!(stiff > 0)) {  // a gas: no contacts to answer yet
      grad[4 * a] = err > 0 ? rate_max : -rate_max;
      continue;
    }
    const double proportional = kBeta * err / (stiff * dt_c);
    integral_[a] = std::clamp(integral_[a] + proportional / kIntegralControls, -rate_max, rate_max);
    grad[4 * a] = std::clamp(proportional + integral_[a], -rate_max, rate_max);
  }
}

bool CellProgramme::compressed(const CellMeasure& m) {
  bool on = true;
  for (int a = 0; a < 3; ++a)
    on = on && std::abs(m.stress[4 * a] - cell_.pressure) < kStressTolerance * cell_.pressure;
  const double mass = density_ * m.solid_fraction * m.volume;
  const double u_rms = std::sqrt(2 * m.kinetic / mass);
  on = on && u_rms < kQuietInertial * std::sqrt(cell_.pressure / density_);
  quiet_ = on ? quiet_ + 1 : 0;
  return quiet_ >= kQuietControls;
}

void CellProgramme::start_test() {
  compress_steps_ = sim_.steps();
  volume0_ = det3(sim_.state().cell_now.h);
  strain_ = 0;
  travel_ = 0;
  next_row_ = cell_.row_strain;
  sum_ = {};
  summed_ = 0;
  if (cell_.test == PeriodicCell::Test::Isotropic) {
    stage_ = Stage::Done;
    sim_.set_cell_gradient(Mat3{});
    return;
  }
  stage_ = Stage::Test;
  apply_friction();
  if (oedometric()) {  // the sides held from the first step of the test on
    Mat3 grad{};
    grad[8] = -test_rate();
    sim_.set_cell_gradient(grad);
  }
}

void CellProgramme::control() {
  const CellMeasure m = measure_cell(sim_);
  const Mat3& s = m.stress;
  const double p = m.pressure();
  CellRow r{};
  r[kColStage] = stage_ == Stage::Compress ? 0 : 1;
  r[kColTime] = sim_.time();
  r[kColStep] = double(sim_.steps());
  r[kColStrain] = strain_;
  r[kColVolumetric] = -std::log(m.volume / volume0_);
  const int at[6] = {0, 4, 8, 1, 2, 5};
  for (int k = 0; k < 6; ++k) r[kColSxx + k] = 1e-3 * s[at[k]];
  r[kColP] = 1e-3 * p;
  r[kColQ] = 1e-3 * deviator(s);
  // simple shear: mu = tau / sigma_zz, tau = -sigma_xz (compression positive,
  // v_x = gamma_dot z: the grains above drag those below along +x)
  r[kColRatio] = cell_.test == PeriodicCell::Test::SimpleShear ? (s[8] != 0 ? -s[2] / s[8] : 0)
                                                               : (p != 0 ? deviator(s) / p : 0);
  r[kColPhi] = m.solid_fraction;
  r[kColVoid] = 1 / m.solid_fraction - 1;
  r[kColZ] = m.coordination;
  r[kColZBackbone] = m.coordination_backbone;
  r[kColFabricAniso] = m.fabric[8] - m.fabric[0];
  r[kColFabricXz] = m.fabric[2];
  r[kColInertial] = p > 0 && stage_ == Stage::Test ? test_rate() * diameter_ * std::sqrt(density_ / p) : 0;
  r[kColKinetic] = m.kinetic;
  for (int k = 0; k < kCellColumns; ++k) sum_[k] += r[k];
  ++summed_;
  ++controls_;
  Mat3 grad = sim_.state().cell_now.grad;
  servo(m, grad);
  if (stage_ == Stage::Test && cell_.test == PeriodicCell::Test::SimpleShear) grad[2] = test_rate();
  if (stage_ == Stage::Test && cell_.test == PeriodicCell::Test::AxialCompression) grad[8] = -test_rate();
  if (stage_ == Stage::Test && oedometric()) oedometric_control(m, grad);
  sim_.set_cell_gradient(grad);
  if (stage_ == Stage::Compress) {
    if (controls_ % kCompressRowControls == 0) add_row();
    if (compressed(m)) {
      add_row();
      start_test();
    }
  } else if (travel_ >= next_row_ - 1e-12) {
    add_row();
    next_row_ += cell_.row_strain;
  }
}

// x and y held (no lateral strain), z shortened at the test's rate until
// sigma_zz reaches the vertical stress (a row there), then lengthened until
// it is back at the pressure.
void CellProgramme::oedometric_control(const CellMeasure& m, Mat3& grad) {
  grad = Mat3{};
  if (!unloading_ && m.stress[8] >= vertical_stress()) {
    unloading_ = true;
    add_row();
  } else if (unloading_ && m.stress[8] <= cell_.pressure) {
    finished_ = true;
  }
  grad[8] = unloading_ ? test_rate() : -test_rate();
}

void CellProgramme::add_row() {
  if (summed_ == 0) return;
  CellRow r = sum_;
  for (double& x : r) x /= summed_;
  r[kColStage] = sum_[kColStage] > 0 ? 1 : 0;
  r[kColTime] = sim_.time();
  r[kColStep] = double(sim_.steps());
  r[kColStrain] = strain_;
  rows_.push_back(r);
  sum_ = {};
  summed_ = 0;
}

bool CellProgramme::advance(std::int64_t max_steps) {
  const std::size_t rows_before = rows_.size();
  const Stage stage_before = stage_;
  while (max_steps > 0 && stage_ != Stage::Done) {
    const std::int64_t steps = std::min<std::int64_t>(max_steps, kControlSteps - since_control_);
    sim_.advance(steps);
    max_steps -= steps;
    since_control_ += steps;
    const Mat3& grad = sim_.state().cell_now.grad;
    if (stage_ == Stage::Test) {
      const double d = steps * sim_.dt() *
                       (cell_.test == PeriodicCell::Test::SimpleShear ? grad[2] : -grad[8]);
      strain_ += d;
      travel_ += std::abs(d);
    }
    if (since_control_ < kControlSteps) break;
    since_control_ = 0;
    control();
    if (stage_ == Stage::Test && (oedometric() ? finished_ : strain_ >= end_strain() - 1e-12)) {
      add_row();
      stage_ = Stage::Done;
      sim_.set_cell_gradient(Mat3{});
    }
    if (rows_.size() != rows_before || stage_ != stage_before) break;
  }
  return rows_.size() != rows_before;
}

LoadingProgramme::StepCount CellProgramme::step_count() const {
  StepCount c;
  c.done = double(sim_.steps());
  const double rate_max = servo_rate_max();
  // the gas to about 0.6 at the servo's fastest rate, twice that for the end
  const double compress = stage_ == Stage::Compress
                              ? 2 * std::log(0.6 / cell_.start_solid_fraction) / 3 / rate_max / sim_.dt()
                              : double(compress_steps_);
  const double test = cell_.test == PeriodicCell::Test::Isotropic ? 0 : end_strain() / test_rate() / sim_.dt();
  c.total = std::max(c.done, compress + test);
  if (stage_ == Stage::Done) c.total = c.done;
  return c;
}

std::string CellProgramme::status() const {
  char buf[200];
  const CellRow* r = rows_.empty() ? nullptr : &rows_.back();
  std::snprintf(buf, sizeof buf, "%s, strain %.4f of %.3g, p %.4g kPa, ratio %.4f, phi %.4f, Z %.3f",
                stage_name(), strain_, end_strain(), r ? (*r)[kColP] : 0.0, r ? (*r)[kColRatio] : 0.0,
                r ? (*r)[kColPhi] : 0.0, r ? (*r)[kColZ] : 0.0);
  return buf;
}

std::string CellProgramme::caption() const {
  char buf[160];
  const CellRow* r = rows_.empty() ? nullptr : &rows_.back();
  const bool shear = cell_.test == PeriodicCell::Test::SimpleShear;
  std::snprintf(buf, sizeof buf, "%s = %.3f, %s = %.3f, Φ = %.3f, p = %.3g kPa", shear ? "γ" : "ε",
                strain_, shear ? "τ/σ" : "q/p", r ? (*r)[kColRatio] : 0.0, r ? (*r)[kColPhi] : 0.0,
                r ? (*r)[kColP] : 0.0);
  return buf;
}

std::string CellProgramme::save_state() const {
  std::ostringstream o;
  o.precision(17);
  o << "cell_test 3\n"
    << static_cast<int>(stage_) << ' ' << strain_ << ' ' << volume0_ << ' ' << next_row_ << ' '
    << quiet_ << ' ' << controls_ << ' ' << compress_steps_ << ' ' << since_control_ << ' '
    << summed_ << ' ' << integral_[0] << ' ' << integral_[1] << ' ' << integral_[2] << ' '
    << travel_ << ' ' << unloading_ << ' ' << finished_ << '\n';
  for (double x : sum_) o << x << ' ';
  o << '\n' << rows_.size() << '\n';
  for (const CellRow& r : rows_) {
    for (double x : r) o << x << ' ';
    o << '\n';
  }
  return o.str();
}

void CellProgramme::restore_state(const std::string& text) {
  std::istringstream in(text);
  std::string tag;
  int version = 0, stage = 0;
  size_t count = 0;
  in >> tag >> version;
  if (tag != "cell_test" || (version != 2 && version != 3))
    throw ReadError("the checkpoint holds no periodic-cell state");
  in >> stage >> strain_ >> volume0_ >> next_row_ >> quiet_ >> controls_ >> compress_steps_ >>
      since_control_ >> summed_ >> integral_[0] >> integral_[1] >> integral_[2];
  travel_ = strain_;  // version 2: a monotonic test, its travel its strain
  unloading_ = finished_ = false;
  if (version == 3) in >> travel_ >> unloading_ >> finished_;
  for (double& x : sum_) in >> x;
  in >> count;
  if (!in || stage < 0 || stage > 2 || count > 10000000 || since_control_ < 0 ||
      since_control_ >= kControlSteps)
    throw ReadError("malformed periodic-cell state");
  stage_ = static_cast<Stage>(stage);
  rows_.assign(count, {});
  for (CellRow& r : rows_)
    for (double& x : r) in >> x;
  if (!in) throw ReadError("malformed periodic-cell rows");
  apply_friction();
}

std::string CellProgramme::rows_csv() const { return cell_rows_csv(rows_); }

CellSummary CellProgramme::summary() const {
  const char* tests[] = {"simple_shear", "triaxial", "isotropic", "oedometric"};
  CellSummary s = cell_summary(rows_, 0.5 * end_strain());
  s.test = tests[static_cast<int>(cell_.test)];
  s.particles = static_cast<int>(sim_.scene().particles.size());
  s.pressure = cell_.pressure;
  s.inertial_number = cell_.inertial_number;
  s.compression_steps = compress_steps_;
  s.steps = sim_.steps();
  return s;
}

std::string CellProgramme::summary_text(double wall_seconds) const {
  CellSummary s = summary();
  s.wall_seconds = wall_seconds;
  std::string text = cell_summary_text(s);
  if (!oedometric()) return text;
  // One-dimensional compression: the void ratio at the start, at the
  // largest vertical stress and back at the pressure, and K0 there.
  const CellRow* first = nullptr;
  const CellRow* top = nullptr;
  for (const CellRow& r : rows_) {
    if (r[kColStage] != 1) continue;
    if (!first) first = &r;
    if (!top || r[kColSzz] > (*top)[kColSzz]) top = &r;
  }
  if (!first) return text;
  const CellRow& last = rows_.back();
  std::ostringstream o;
  o.precision(6);
  o << "oedometric_vertical_stress_max_kPa = " << (*top)[kColSzz]
    << "\noedometric_void_ratio_start = " << (*first)[kColVoid]
    << "\noedometric_void_ratio_at_max = " << (*top)[kColVoid]
    << "\noedometric_void_ratio_end = " << last[kColVoid]
    << "\noedometric_k0_at_max = " << ((*top)[kColSxx] + (*top)[kColSyy]) / (2 * (*top)[kColSzz]) << "\n";
  const size_t at = text.rfind("wall_seconds");
  return at == std::string::npos ? text + o.str() : text.insert(at, o.str());
}

std::string CellProgramme::describe() const {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "periodic cell, stress servo beta %.2g every %d steps, fastest strain rate %.4g 1/s",
                kBeta, kControlSteps,
                servo_rate_max());
  return buf;
}

std::string CellProgramme::measuring_line() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, "testing at %.4g 1/s (inertial number %.3g)", test_rate(),
                cell_.inertial_number);
  return buf;
}

}  // namespace simsols
