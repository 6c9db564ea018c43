#include "app/experiment/shear_box/study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>

#include "render/plot/chart.h"
#include "solver/io/checkpoint.h"
#include "solver/scene/contact_model.h"
#include "solver/common/errors.h"
#include "solver/io/output.h"
#include "app/experiment/shear_box/paper_tests.h"
#include "solver/io/scene_toml.h"
#include "app/experiment/shear_box/shear_run.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "app/experiment/shear_box/study_ensemble.h"
#include "solver/core/simulation.h"

namespace simsols {

namespace {

using Clock = std::chrono::steady_clock;

StudySettings make(const char* knob, const char* label, double dt, Precision p = Precision::Float,
                   double e = 1, double inertial = 8e-4, double skin = 0.1, bool rolling = true,
                   bool damping = true) {
  return {knob, label, dt, p, e, inertial, skin, rolling, damping};
}

std::vector<StudySettings> sweep() {
  const Precision F = Precision::Float, D = Precision::Double;
  return {
      // the most accurate settings of the sweep: the reference for the shear test
      make("reference", "reference: dt 0.10 double I 2e-4", 0.10, D, 1, 2e-4),
      make("baseline", "baseline: dt 0.25 float I 8e-4", 0.25),
      make("time step", "dt 0.05", 0.05),
      make("time step", "dt 0.10", 0.10),
      make("time step", "dt 0.50", 0.50),
      make("time step", "dt 0.75 (forced)", 0.75),
      make("time step", "dt 1.0 (forced)", 1.0),
      make("time step", "dt 2.0 (forced)", 2.0),
      make("precision", "double", 0.25, D),
      make("stiffness", "E x 0.1", 0.25, F, 0.1),
      make("stiffness", "E x 0.01", 0.25, F, 0.01),
      make("inertial number", "I 1e-4", 0.25, F, 1, 1e-4),
      make("inertial number", "I 4e-4", 0.25, F, 1, 4e-4),
      make("inertial number", "I 2e-3", 0.25, F, 1, 2e-3),
      make("inertial number", "I 1e-2", 0.25, F, 1, 1e-2),
      make("skin", "skin 0.03 d", 0.25, F, 1, 8e-4, 0.03),
      make("skin", "skin 0.3 d", 0.25, F, 1, 8e-4, 0.3),
      make("effects", "no rolling friction", 0.25, F, 1, 8e-4, 0.1, false, true),
      make("effects", "no damping", 0.25, F, 1, 8e-4, 0.1, true, false),
      make("combination", "E x 0.1 + dt 0.5", 0.5, F, 0.1),
      make("combination", "E x 0.01 + dt 0.5 + I 2e-3", 0.5, F, 0.01, 2e-3),
      make("combination", "dt 0.5 + I 2e-3", 0.5, F, 1, 2e-3),
  };
}

Material glass_scaled(double scale) {
  Material m = paper_glass();
  m.young_modulus *= scale;
  return m;
}

Scene contact_scene(const StudySettings& s, const Material& m) {
  Scene sc;
  sc.name = "contact check";
  sc.materials = {m};
  sc.effects.gravity = {0, 0, 0};
  sc.effects.rolling = s.rolling ? RollingModel::ConstantTorque : RollingModel::None;
  sc.effects.damping = s.damping ? DampingModel::Viscous : DampingModel::None;
  sc.numerics.precision = s.precision;
  sc.numerics.dt_fraction = s.dt_fraction;
  sc.numerics.force_dt = s.dt_fraction > kMaxDtFraction;
  sc.numerics.duration = 1;
  Wall floor;
  floor.name = "floor";
  sc.walls = {floor};
  return sc;
}

double pct(double measured, double theory) { return 100 * std::fabs(measured / theory - 1); }

// The settings of `labels`, in that order, from the sweep.
std::vector<StudySettings> pick(std::initializer_list<const char*> labels) {
  std::vector<StudySettings> all = sweep(), out;
  for (const char* label : labels)
    for (const StudySettings& s : all)
      if (s.label == label) out.push_back(s);
  return out;
}

// The quick preset's settings: one step each way on the knobs that matter
// most, so that its ensembles cost about what one run per setting of the
// whole sweep did.
std::vector<StudySettings> quick_sweep() {
  return pick({"reference: dt 0.10 double I 2e-4", "baseline: dt 0.25 float I 8e-4", "dt 0.10",
               "dt 0.50", "double", "E x 0.1", "I 2e-3", "no rolling friction"});
}

std::vector<StudySettings> joined(std::vector<StudySettings> a, const std::vector<StudySettings>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The poured specimen's (quick): a reference at the baseline's shear speed
// (its runs cost ~2.5x the layered ones', and the reference's slower shear
// 4x more again), and the cheaper settings a user would pick for a random
// specimen. The full preset sweeps all of them against the full reference.
std::vector<StudySettings> poured_sweep(bool full) {
  std::vector<StudySettings> out =
      full ? sweep()
           : joined({make("reference", "reference: dt 0.10 double I 8e-4", 0.10, Precision::Double)},
                    pick({"baseline: dt 0.25 float I 8e-4", "dt 0.50", "E x 0.1", "I 2e-3"}));
  for (StudySettings& s : out) s.specimen = StudySpecimen::Poured;
  return out;
}

}  // namespace

double ContactErrors::worst() const {
  return std::max({overlap, force, duration, restitution, rolling});
}

std::optional<StudyPreset> study_preset(const std::string& name, int ensemble) {
  StudyPreset p;
  p.name = name;
  if (name == "quick") {
    p.cases = joined(quick_sweep(), poured_sweep(false));
    p.ensemble = 3;
  } else if (name == "full") {
    p.displacement_mm = 6;
    p.rows = 300;
    p.cases = joined(sweep(), poured_sweep(true));
    p.ensemble = 5;
  } else if (name == "ci") {
    // reduced: two layers, 0.3 mm of shear, few cases
    p.layers = 2;
    const Precision D = Precision::Double;
    p.displacement_mm = 0.3;
    p.rows = 20;
    p.cases = {make("reference", "reference: dt 0.15 double", 0.15, D),
               make("time step", "dt 0.2", 0.2),
               make("time step", "dt 0.4", 0.4),
               make("precision", "double dt 0.2", 0.2, D),
               make("time step", "dt 3.0 (forced)", 3.0)};
    // the poured specimen in a box 0.7 x the paper's, its rain not quite settled
    p.poured_box_scale = 0.7;
    p.poured_settle_time = 0.05;
    for (StudySettings s : {make("reference", "reference: dt 0.2 double", 0.2, D),
                            make("time step", "dt 0.4", 0.4)}) {
      s.specimen = StudySpecimen::Poured;
      p.cases.push_back(s);
    }
    p.ensemble = 2;
  } else {
    return std::nullopt;
  }
  if (ensemble > 0) p.ensemble = ensemble;
  return p;
}

std::vector<StudySettings> study_runs(const StudyPreset& preset,
                                      const std::vector<StudySettings>& settings) {
  std::vector<StudySettings> runs;
  std::optional<StudySettings> shear_twin;  // the specimen's last run
  for (size_t i = 0; i < settings.size(); ++i) {
    for (int seed = 1; seed <= preset.ensemble; ++seed) {
      StudySettings m = settings[i];
      m.seed = seed;
      runs.push_back(m);
    }
    if (settings[i].knob == "reference" && preset.shear) {
      StudySettings twin = settings[i];
      twin.knob = kTwinKnob;
      twin.label = settings[i].label + " (round-off twin)";
      twin.perturbation = kRoundOffPerturbation;
      runs.push_back(twin);
      if (settings[i].specimen == StudySpecimen::Poured) {
        twin.knob = kShearTwinKnob;
        twin.label = settings[i].label + " (round-off twin at shear)";
        twin.perturb_at_shear = true;
        shear_twin = twin;
      }
    }
    const bool last_of_specimen =
        i + 1 == settings.size() || settings[i + 1].specimen != settings[i].specimen;
    if (last_of_specimen && shear_twin) {
      runs.push_back(*shear_twin);
      shear_twin.reset();
    }
  }
  return runs;
}

namespace {

// A measurement that could not be made (the case fails and says why; the
// study goes on with the other cases).
struct CaseFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr double kCheckRadius = 6.35e-3 / 2;  // the paper's largest beads

// A Hertz impact on a wall, elastic and frictionless, at 0.1 m/s: overlap,
// force and duration against Hertz's theory.
void check_hertz_impact(const StudySettings& s, const std::shared_ptr<Device>& device,
                        ContactErrors& e) {
  const double R = kCheckRadius;
  Material m = glass_scaled(s.stiffness_scale);
  m.restitution = 1;
  m.sliding_friction = 0;
  m.rolling_friction = 0;
  Scene sc = contact_scene(s, m);
  const double v = 0.1;
  Particle p;
  p.radius = R;
  p.position = {0, 0, R + 1e-7};
  p.velocity = {0, 0, -v};
  sc.particles = {p};
  const double mass = m.density * 4.0 / 3 * std::numbers::pi * R * R * R;
  const double es = m.young_modulus / (2 * (1 - m.poisson_ratio * m.poisson_ratio));
  const double dmax = std::pow(15 * mass * v * v / (16 * es * std::sqrt(R)), 0.4);
  const double fmax = 4.0 / 3 * es * std::sqrt(R) * std::pow(dmax, 1.5);
  const double tc = 2 * std::sqrt(std::numbers::pi) * std::tgamma(1.4) / std::tgamma(0.9) * dmax / v;
  Simulation sim(device, sc);
  // contact time: the zero crossings of the overlap, interpolated
  // linearly between steps (not a count of whole steps)
  double overlap = 0, force = 0, t_in = -1, t_out = -1, prev = R - sc.particles[0].position[2];
  double prev_t = 0;
  for (int i = 0; i < 200000 && t_out < 0; ++i) {
    sim.advance(1);
    const ParticleSnapshot q = sim.snapshot();
    if (!std::isfinite(q.position[0][2])) throw CaseFailed("NaN in the impact");
    const double d = R - q.position[0][2];
    if (t_in < 0 && d > 0) t_in = prev_t + (0 - prev) / (d - prev) * (sim.time() - prev_t);
    if (t_in >= 0 && d <= 0 && prev > 0)
      t_out = prev_t + (0 - prev) / (d - prev) * (sim.time() - prev_t);
    overlap = std::max(overlap, d);
    force = std::max(force, norm(q.force[0]));
    prev = d;
    prev_t = sim.time();
  }
  if (t_out < 0) throw CaseFailed("the impact never ended");
  const double duration = t_out - t_in;
  e.overlap = pct(overlap, dmax);
  e.force = pct(force, fmax);
  e.duration = pct(duration, tc);
}

// The restitution of a damped impact on a wall at 0.1 m/s, against the
// material's coefficient.
void check_restitution(const StudySettings& s, const std::shared_ptr<Device>& device,
                       ContactErrors& e) {
  const double R = kCheckRadius;
  Material m = glass_scaled(s.stiffness_scale);
  m.sliding_friction = 0;
  m.rolling_friction = 0;
  Scene sc = contact_scene(s, m);
  Particle p;
  p.radius = R;
  p.position = {0, 0, R + 1e-7};
  p.velocity = {0, 0, -0.1};
  sc.particles = {p};
  Simulation sim(device, sc);
  if (!advance_through_contact(sim, 0, 200000))
    throw CaseFailed("the damped impact never ended");
  const double out = sim.snapshot().velocity[0][2] / 0.1;
  if (!std::isfinite(out) || out > 1.0001)
    throw CaseFailed("the impact created energy (e = " + std::to_string(out) + ")");
  e.restitution = pct(out, s.damping ? m.restitution : 1.0);
}

// Sliding to rolling on a floor (mu = 0.5, v0 = 0.05 m/s): the time to pure
// rolling against 2 v0 / (7 mu g).
void check_rolling_onset(const StudySettings& s, const std::shared_ptr<Device>& device,
                         ContactErrors& e) {
  const double R = kCheckRadius;
  Material m = glass_scaled(s.stiffness_scale);
  m.sliding_friction = 0.5;
  m.rolling_friction = 0;
  Scene sc = contact_scene(s, m);
  const double g = 9.81, v0 = 0.05, mu = 0.5;
  sc.effects.gravity = {0, 0, -g};
  Particle p;
  p.radius = R;
  const double mass = m.density * 4.0 / 3 * std::numbers::pi * R * R * R;
  const double es = m.young_modulus / (2 * (1 - m.poisson_ratio * m.poisson_ratio));
  p.position = {0, 0, R - std::pow(mass * g / (4.0 / 3 * es * std::sqrt(R)), 2.0 / 3)};
  p.velocity = {v0, 0, 0};
  sc.particles = {p};
  Simulation sim(device, sc);
  const double t_theory = 2 * v0 / (7 * mu * g);
  double t_roll = -1, prev_slip = v0, prev_t = 0;
  while (sim.time() < 3 * t_theory) {
    sim.advance(1);
    const ParticleSnapshot q = sim.snapshot();
    const double slip = q.velocity[0][0] - q.angular_velocity[0][1] * R;
    if (!std::isfinite(slip)) throw CaseFailed("NaN while rolling");
    if (slip <= 1e-3 * v0) {
      const double f = (prev_slip - 1e-3 * v0) / (prev_slip - slip);
      t_roll = prev_t + f * (sim.time() - prev_t);
      break;
    }
    prev_slip = slip;
    prev_t = sim.time();
  }
  if (t_roll < 0) throw CaseFailed("never reached rolling");
  e.rolling = pct(t_roll, t_theory);
}

}  // namespace

ContactErrors run_contact_checks(const StudySettings& s, std::shared_ptr<Device> device) {
  ContactErrors e;
  try {
    check_hertz_impact(s, device, e);
    check_restitution(s, device, e);
    check_rolling_onset(s, device, e);
    e.ok = true;
  } catch (const std::exception& x) {
    e.ok = false;
    e.failure = x.what();
  }
  return e;
}

namespace {

Scene shear_case_scene(const StudyPreset& preset, const StudySettings& s) {
  const Scene base = default_shear_base();
  const double d = preset.diameter_mm * 1e-3;
  Scene sc = paper_test_scene(
      base, kDefaultSceneName, preset.diameter_mm, preset.stress_kpa, preset.layers,
      [&](Scene& x) {
        x.numerics.precision = s.precision;
        x.numerics.dt_fraction = s.dt_fraction;
        x.numerics.dt = 0;
        x.numerics.force_dt = s.dt_fraction > kMaxDtFraction;
        x.numerics.skin = s.skin_factor * d;
        for (Material& m : x.materials) m.young_modulus *= s.stiffness_scale;
        x.effects.rolling = s.rolling ? RollingModel::ConstantTorque : RollingModel::None;
        x.effects.damping = s.damping ? DampingModel::Viscous : DampingModel::None;
        ShearBox& box = *x.apparatus_as<ShearBox>();
        box.inertial_number = s.inertial_number;
        box.shear_speed = 0;
        box.shear_displacement = preset.displacement_mm * 1e-3;
        box.rows = preset.rows;
        box.specimen.seed = s.seed;
        if (s.specimen == StudySpecimen::Poured) {
          box.specimen.method = Specimen::Method::Pour;
          box.length *= preset.poured_box_scale;
          box.width *= preset.poured_box_scale;
          box.settle_time = preset.poured_settle_time;
        }
      });
  if (s.perturbation != 0 && !s.perturb_at_shear && !sc.particles.empty())
    sc.particles[0].position[0] += s.perturbation * d;
  return sc;
}

// Throws when the run broke (NaN, beads out, a neighbour list outrun).
void check_case(Simulation& sim, const ShearProgramme& test) {
  if (!test.rows().empty()) {
    const ShearRow& row = test.rows().back();
    if (!std::isfinite(row.tau) || !std::isfinite(row.dilation))
      throw CaseFailed("NaN in the measurements");
    if (row.outside > 0)
      throw CaseFailed(std::to_string(row.outside) + " beads left the box");
  }
  if (sim.state().late_builds > 0)
    throw CaseFailed("a bead outran its neighbour list (skin too small for the step)");
}

}  // namespace

ShearResult run_shear_case(const StudyPreset& preset, const StudySettings& s,
                           const ShearCaseControl& control) {
  const std::shared_ptr<Device> device = control.device;
  ShearResult r;
  try {
    std::unique_ptr<Simulation> sim;
    std::string state;
    double wall_before = 0;
    if (!control.checkpoint.empty() && std::filesystem::exists(control.checkpoint)) {
      sim = load_checkpoint(device, control.checkpoint, &state);
      wall_before = driver_wall_seconds(state);
    } else {
      sim = std::make_unique<Simulation>(device, shear_case_scene(preset, s));
    }
    ShearProgramme test(*sim);
    if (!state.empty()) {
      test.restore_state(state);
      std::fprintf(stderr, "[study] case resumed at %s\n", where_test_is(*sim, test).c_str());
    } else if (s.perturb_at_shear) {
      test.hold_before_shear(true);  // until the bead is moved, below
    }
    const auto t0 = Clock::now();
    while (!test.done()) {
      if (control.stop_requested && control.stop_requested()) {
        const double wall = wall_before + std::chrono::duration<double>(Clock::now() - t0).count();
        save_checkpoint(*sim, control.checkpoint, driver_state(test, wall));
        r.interrupted = true;
        return r;
      }
      test.advance(5000);  // returns at each check: a held test is ready at the member's step
      if (s.perturb_at_shear && test.ready_to_shear()) {
        sim->nudge_particle(0, {s.perturbation * test.bead_diameter(), 0, 0});
        test.start_shear();
      }
      check_case(*sim, test);
      const Observables o = sim->steps() % 50000 < 5000 ? sim->observe() : Observables{};
      if (!std::isfinite(o.kinetic())) throw CaseFailed("NaN in the kinetic energy");
    }
    r.wall_seconds = wall_before + std::chrono::duration<double>(Clock::now() - t0).count();
    const ShearSummary sum = test.summary();
    // phi_peak: the first peak, as every summary reads it (shear_analysis.h)
    r.peak_angle = sum.peak_angle;
    for (const ShearRow& row : test.rows()) {
      r.curve_mm.push_back(row.displacement * 1e3);
      r.curve_ratio.push_back(row.sigma > 0 ? row.tau / row.sigma : 0);
    }
    r.residual_angle = sum.residual_angle;
    r.dilatancy_angle = sum.max_dilatancy_angle;
    r.steps = sim->steps();
    r.list_builds = sim->state().list_builds;
    r.particles = sim->model().particles();
    r.particle_steps_per_second = r.wall_seconds > 0 ? double(r.particles) * r.steps / r.wall_seconds : 0;
    if (!std::isfinite(r.peak_angle) || !std::isfinite(r.residual_angle))
      throw CaseFailed("NaN in the summary");
    r.ok = true;
  } catch (const SceneError&) {
    throw;  // a damaged case checkpoint is the user's to hear about, not a failed case
  } catch (const std::exception& x) {
    r.ok = false;
    r.failure = x.what();
  }
  return r;
}

void compare_to_reference(std::vector<StudyCase>& cases) {
  auto rel = [](double a, double b) { return b != 0 ? 100 * std::fabs(a - b) / std::fabs(b) : 0.0; };
  for (StudySpecimen specimen : kStudySpecimens) {
    ShearResult ref;  // the mean of the specimen's reference's members
    int n = 0;
    for (const StudyCase& c : cases)
      if (c.settings.specimen == specimen && c.settings.knob == "reference" && c.shear.ok) {
        ref.peak_angle += c.shear.peak_angle;
        ref.residual_angle += c.shear.residual_angle;
        ref.dilatancy_angle += c.shear.dilatancy_angle;
        ++n;
      }
    if (n == 0) continue;
    for (StudyCase& c : cases) {
      if (!c.shear.ok || c.settings.specimen != specimen) continue;
      c.peak_error = rel(c.shear.peak_angle, ref.peak_angle / n);
      c.residual_error = rel(c.shear.residual_angle, ref.residual_angle / n);
      c.dilatancy_error = rel(c.shear.dilatancy_angle, ref.dilatancy_angle / n);
    }
  }
}

namespace {

std::string num(double v, const char* f = "%.6g") { return format_number(f, v); }

}  // namespace

std::string study_csv(const std::vector<StudyCase>& cases) {
  std::string o = std::string(kSettingsCsvHeader) +
      ",contact_status,overlap_err_pct,force_err_pct,contact_time_err_pct,"
      "restitution_err_pct,rolling_time_err_pct,shear_status,peak_deg,residual_deg,"
      "dilatancy_deg,peak_err_pct,residual_err_pct,dilatancy_err_pct,wall_s,"
      "particle_steps_per_s,steps,list_builds,seed,perturbation_d\n";
  for (const StudyCase& c : cases) {
    const StudySettings& s = c.settings;
    o += settings_csv_cells(s) + ",";
    if (c.contact.ok)
      o += "ok," + num(c.contact.overlap) + "," + num(c.contact.force) + "," +
           num(c.contact.duration) + "," + num(c.contact.restitution) + "," +
           num(c.contact.rolling) + ",";
    else
      o += csv_quoted("failed: " + c.contact.failure) + ",,,,,,";
    if (c.shear.ok) {
      auto opt = [](const std::optional<double>& v) { return v ? num(*v) : std::string(); };
      o += "ok," + num(c.shear.peak_angle) + "," + num(c.shear.residual_angle) + "," +
           num(c.shear.dilatancy_angle) + "," + opt(c.peak_error) + "," + opt(c.residual_error) +
           "," + opt(c.dilatancy_error) + "," + num(c.shear.wall_seconds, "%.2f") + "," +
           num(c.shear.particle_steps_per_second, "%.4g") + "," + std::to_string(c.shear.steps) +
           "," + std::to_string(c.shear.list_builds);
    } else {
      o += csv_quoted(c.shear.failure.empty() ? "not run" : "failed: " + c.shear.failure) +
           ",,,,,,,,,,";
    }
    o += "," + std::to_string(s.seed) + "," + num(s.perturbation) + "\n";
  }
  return o;
}

namespace {

// The 95 % upper bound of a setting's |error| (deg): on phi_peak, and for
// the poured specimen the larger of phi_peak's and phi_res's (its residual
// is a result of its own); NaN when unknown.
double bound_of(const std::optional<Interval>& e) {
  return e ? std::fabs(e->mean) + e->half_width : std::numeric_limits<double>::quiet_NaN();
}
double error_bound(const SettingSummary& s) {
  if (s.settings.specimen == StudySpecimen::Layered) return bound_of(s.peak_error);
  return std::max(bound_of(s.peak_error), bound_of(s.residual_error));
}

std::string file_part(std::string k) {
  for (char& c : k)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return k;
}

// "" for the layered specimen's files, "poured_" for the poured one's.
std::string file_prefix(StudySpecimen s) {
  return s == StudySpecimen::Layered ? "" : std::string(specimen_name(s)) + "_";
}

// One series of errors (with their 95 % intervals as bars) against the
// wall time per run, of the settings of knob `k` and the reference and
// baseline.
plot::Series error_series(const std::vector<SettingSummary>& set, const std::string& k,
                          const char* name, std::optional<Interval> SettingSummary::*which,
                          bool line, std::vector<plot::Marker>* markers) {
  plot::Series sr{name, {}, {}, std::nullopt, line, true, false, {}};
  for (const SettingSummary& s : set) {
    const std::optional<Interval>& e = s.*which;
    if (!e || (s.settings.knob != k && s.settings.knob != "baseline" && s.settings.knob != "reference"))
      continue;
    sr.x.push_back(s.wall_seconds);
    sr.y.push_back(e->mean);
    sr.y_err.push_back(e->half_width);
    if (markers) markers->push_back({s.wall_seconds, e->mean, s.settings.label});
  }
  return sr;
}

// Errors of phi_peak and phi_res (the ensemble means' differences from the
// reference's) against the wall time per run: one chart per knob.
void write_knob_charts(const std::filesystem::path& dir, const std::vector<SettingSummary>& set,
                       StudySpecimen specimen) {
  std::vector<std::string> knobs;
  for (const SettingSummary& s : set)
    if (s.peak_error && s.settings.knob != "reference" && s.settings.knob != "baseline" &&
        std::find(knobs.begin(), knobs.end(), s.settings.knob) == knobs.end())
      knobs.push_back(s.settings.knob);
  for (const std::string& k : knobs) {
    plot::Chart ch;
    ch.title = "Accuracy against cost, " + std::string(specimen_name(specimen)) + " specimen: " + k;
    ch.x_label = "wall time per run of the shear test (s)";
    ch.y_label = "error vs reference (°, 95 % interval)";
    ch.series.push_back(error_series(set, k, "φ_peak", &SettingSummary::peak_error, false, &ch.markers));
    ch.series.push_back(error_series(set, k, "φ_res", &SettingSummary::residual_error, false, nullptr));
    plot::write_chart_png(
        ch, (dir / (file_prefix(specimen) + "error_vs_time_" + file_part(k) + ".png")).string());
  }
}

// The Pareto front: the settings no other beats on both cost and the 95 %
// bound of |error| (error_bound).
void write_pareto_chart(const std::filesystem::path& dir, const std::vector<SettingSummary>& set,
                        StudySpecimen specimen) {
  std::vector<const SettingSummary*> ok;
  for (const SettingSummary& s : set)
    if (std::isfinite(error_bound(s))) ok.push_back(&s);
  if (ok.empty()) return;
  std::sort(ok.begin(), ok.end(), [](auto* a, auto* b) { return a->wall_seconds < b->wall_seconds; });
  plot::Chart pc;
  pc.title = "Pareto front, " + std::string(specimen_name(specimen)) +
             " specimen: the cheapest setting for a given error";
  pc.x_label = "wall time per run of the shear test (s)";
  pc.y_label = specimen == StudySpecimen::Layered
                   ? "|error| of φ_peak, 95 % upper bound (°)"
                   : "|error| of φ_peak and φ_res, the larger 95 % bound (°)";
  plot::Series all{"all settings", {}, {}, std::nullopt, false, true, false, {}};
  plot::Series fr{"Pareto front", {}, {}, std::nullopt, true, true, false, {}};
  double best = 1e300;
  for (const SettingSummary* s : ok) {
    all.x.push_back(s->wall_seconds);
    all.y.push_back(error_bound(*s));
    if (error_bound(*s) < best) {
      best = error_bound(*s);
      fr.x.push_back(s->wall_seconds);
      fr.y.push_back(best);
      pc.markers.push_back({s->wall_seconds, best, s->settings.label});
    }
  }
  pc.series = {all, fr};
  pc.y_min = 0;
  plot::write_chart_png(pc, (dir / (file_prefix(specimen) + "pareto.png")).string());
}

}  // namespace

void write_study_outputs(const std::string& dir, const StudyPreset& preset,
                         const std::vector<StudyCase>& cases) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  write_file_atomic((fs::path(dir) / "cases.csv").string(), study_csv(cases));
  if (cases.empty()) return;
  const std::vector<SettingSummary> settings = summarise_settings(cases);
  write_file_atomic((fs::path(dir) / "ensemble.csv").string(), ensemble_csv(settings));
  write_file_atomic((fs::path(dir) / "summary.md").string(),
                    ensemble_summary_md(preset, settings, cases));
  write_study_charts(dir, settings);
}

void write_study_charts(const std::string& dir, const std::vector<SettingSummary>& settings) {
  std::filesystem::create_directories(dir);
  for (StudySpecimen specimen : kStudySpecimens) {
    const std::vector<SettingSummary> of = settings_of(settings, specimen);
    write_knob_charts(dir, of, specimen);
    write_pareto_chart(dir, of, specimen);
  }
}

}  // namespace simsols
