#include "app/experiment/shape_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "app/experiment/progress.h"
#include "render/plot/chart.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "solver/common/errors.h"
#include "solver/common/line_fit.h"
#include "solver/core/simulation.h"
#include "solver/io/output.h"
#include "solver/io/scene_toml.h"
#include "solver/scene/clump.h"

namespace simsols {
namespace {

constexpr double kG = 9.81;
constexpr double kColumnLength = 10, kColumnWidth = 5;  // the column, in grain diameters
constexpr double kShearStress = 10e3;                    // Pa

// The softened glass of every case, and its grain (a template's size is
// its volume-equivalent diameter; listed spheres are as listed).
std::string material_and_grain(const ShapeCase& c, double d) {
  std::ostringstream o;
  o.precision(17);
  o << "[[materials]]\nname = \"grain\"\nyoung_modulus = 3e8\npoisson_ratio = 0.2\n"
       "density = 2650\nrestitution = 0.5\nsliding_friction = 0.5\nrolling_friction = "
    << c.rolling_friction << "\n\n[[grains]]\nname = \"g\"\n" << c.grain_keys << "\n";
  if (c.grain_keys.rfind("spheres = ", 0) != 0) o << "diameter = " << d << "\n";
  if (!c.rolling.empty()) o << "\n[effects]\nrolling = \"" << c.rolling << "\"\n";
  o << "\n[numerics]\nprecision = \"float\"\nduration = 100\n";
  return o.str();
}

// A pour of the grains in a cell of length x width (an oedometer's, whose
// placement every apparatus shares: specimen.h).
std::string poured_scene(const ShapePreset& p, const ShapeCase& c, double length, double width,
                         int layers) {
  std::ostringstream o;
  o.precision(17);
  o << material_and_grain(c, p.diameter) << "\n[oedometer]\nlength = " << length
    << "\nwidth = " << width << "\nwall_material = \"grain\"\nload_steps = [1e3, 2e3]\n\n"
       "[oedometer.specimen]\nmethod = \"pour\"\nmaterial = \"grain\"\ngrain = \"g\"\n"
       "diameter = " << p.diameter << "\nlayers = " << layers << "\nseed = 1\n";
  return o.str();
}

Wall plane(const char* name, const Vec3& point, const Vec3& normal) {
  Wall w;
  w.name = name;
  w.point = point;
  w.normal = normal;
  return w;
}

// The column behind its gate: the pour, in a cell of floor, back wall,
// side walls and gate (the last), all of the grains' material.
Scene column(const ShapePreset& p, const ShapeCase& c) {
  const double a = kColumnLength * p.diameter, w = kColumnWidth * p.diameter;
  Scene s = parse_scene(poured_scene(p, c, a, w, p.column_layers), "shape study column (" + c.label + ")");
  s.apparatus = {};
  s.walls = {plane("floor", {0, 0, 0}, {0, 0, 1}), plane("back", {0, 0, 0}, {1, 0, 0}),
             plane("left", {0, 0, 0}, {0, 1, 0}), plane("right", {0, w, 0}, {0, -1, 0}),
             plane("gate", {a, 0, 0}, {-1, 0, 0})};
  return s;
}

// Runs until the grains' kinetic energy is below 1e-4 m g d per grain
// (after `least` s), or for `most` s; the simulated time taken.
double until_at_rest(Simulation& sim, double least, double most, double grain_weight_d,
                     const std::string& what, const ShapeLog& log) {
  const double t0 = sim.time();
  const std::int64_t chunk = std::max<std::int64_t>(1, std::llround(2e-3 / sim.dt()));
  const int grains = std::max<int>(1, static_cast<int>(sim.scene().clumps.size()));
  Ticker ticker;
  while (sim.time() - t0 < most) {
    sim.advance(chunk);
    if (ticker.due() && log) {
      char line[160];
      std::snprintf(line, sizeof line, "%s, t = %.3f s of at most %.2f s, step %lld, %.0f s", what.c_str(),
                    sim.time() - t0, most, static_cast<long long>(sim.steps()), ticker.elapsed());
      log(line);
    }
    if (sim.time() - t0 < least) continue;
    if (sim.observe().kinetic() < 1e-4 * grains * grain_weight_d) break;
  }
  return sim.time() - t0;
}

// The heap's profile: the highest grain top in each strip of width d/2.
void heap_profile(Simulation& sim, double d, ReposeResult& r) {
  const ParticleSnapshot snap = sim.snapshot();
  double far = 0;
  for (size_t i = 0; i < snap.position.size(); ++i)
    far = std::max(far, snap.position[i][0] + snap.radius[i]);
  const double strip = d / 2;
  const int n = std::max(1, static_cast<int>(std::ceil(far / strip)));
  r.x.assign(n, 0);
  r.top.assign(n, 0);
  for (int k = 0; k < n; ++k) r.x[k] = (k + 0.5) * strip;
  for (size_t i = 0; i < snap.position.size(); ++i) {
    const int k = std::clamp(static_cast<int>(snap.position[i][0] / strip), 0, n - 1);
    r.top[k] = std::max(r.top[k], snap.position[i][2] + snap.radius[i]);
  }
  r.runout = far;
  r.height = *std::max_element(r.top.begin(), r.top.end());
  r.angle = repose_angle(r.x, r.top, d, &r.fit_rms);
}

// Runs the collapse until the heap's surface rests: no strip's top moved
// more than d/20 in 0.05 s, twice running (beads that roll off over the
// floor, never stopped without rolling resistance, are no part of the
// heap), or for `limit` s. The profile then in `r`; the simulated time taken.
double until_heap_rests(Simulation& sim, double d, double limit, const ShapeLog& log,
                        ReposeResult& r) {
  const double t0 = sim.time();
  const std::int64_t chunk = std::max<std::int64_t>(1, std::llround(0.05 / sim.dt()));
  Ticker ticker;
  heap_profile(sim, d, r);
  int still = 0;
  while (sim.time() - t0 < limit && still < 2) {
    const std::vector<double> before = r.top;
    sim.advance(chunk);
    heap_profile(sim, d, r);
    double moved = 0;
    for (size_t k = 0; k < before.size() && k < r.top.size(); ++k)
      if (before[k] >= 0.2 * r.height) moved = std::max(moved, std::abs(r.top[k] - before[k]));
    still = sim.time() - t0 > 0.1 && moved < d / 20 ? still + 1 : 0;
    if (ticker.due() && log) {
      char line[160];
      std::snprintf(line, sizeof line, "collapse, t = %.3f s of at most %g s, heap %.1f deg, step %lld, %.0f s",
                    sim.time() - t0, limit, r.angle, static_cast<long long>(sim.steps()), ticker.elapsed());
      log(line);
    }
  }
  return sim.time() - t0;
}

ReposeResult run_repose(const ShapePreset& p, const Scene& scene, const std::shared_ptr<Device>& device,
                        const ShapeLog& log) {
  Simulation sim(device, scene);
  const GrainBody body = grain_body(scene.grains[0]);
  const double grain_mass = scene.materials[0].density * body.mass.volume;
  ReposeResult r;
  r.grains = static_cast<int>(scene.clumps.size());
  r.spheres = static_cast<int>(scene.particles.size());
  const double weight_d = grain_mass * kG * p.diameter;
  r.fill_time = until_at_rest(sim, 0.05, 0.6, weight_d, "column settling", log);
  const int gate = static_cast<int>(scene.walls.size()) - 1;
  sim.set_wall_point(gate, {10.0, 0, 0});  // taken away: far beyond any run-out
  r.collapse_time = until_heap_rests(sim, p.diameter, p.collapse_limit, log, r);
  if (p.hold > 0) {  // the rested heap, watched longer: does it slump?
    ReposeResult later;
    sim.advance(std::llround(p.hold / sim.dt()));
    heap_profile(sim, p.diameter, later);
    r.height_later = later.height;
    r.angle_later = later.angle;
  }
  return r;
}

std::string shear_scene(const ShapePreset& p, const ShapeCase& c) {
  const double l = 10 * p.diameter;
  std::ostringstream o;
  o.precision(17);
  o << material_and_grain(c, p.diameter) << "\n[shear_box]\nlength = " << l << "\nwidth = " << l
    << "\nnormal_stress = " << kShearStress << "\nshear_displacement = " << p.shear_fraction * l
    << "\nsettle_time = 0.3\nrows = 60\nwall_material = \"grain\"\n\n[shear_box.specimen]\n"
       "method = \"pour\"\nmaterial = \"grain\"\ngrain = \"g\"\ndiameter = "
    << p.diameter << "\nlayers = " << p.shear_layers << "\nseed = 1\n";
  return o.str();
}

void run_shear(const ShapePreset& p, const ShapeCase& c, const std::shared_ptr<Device>& device,
               const ShapeLog& log, ShapeResult& r) {
  Simulation sim(device, parse_scene(shear_scene(p, c), "shape study shear box (" + c.label + ")"));
  ShearProgramme test(sim);
  Ticker ticker;
  while (!test.done()) {
    test.advance(5000);
    if (!ticker.due() || !log) continue;
    char line[160];
    std::snprintf(line, sizeof line, "shear box: %s, t = %.3f s, step %lld, %.0f s", test.stage_name(),
                  sim.time(), static_cast<long long>(sim.steps()), ticker.elapsed());
    log(line);
  }
  r.shear = test.summary();
  for (const ShearRow& row : test.rows()) {
    r.shear_mm.push_back(row.displacement * 1e3);
    r.shear_ratio.push_back(row.sigma > 0 ? row.tau / row.sigma : 0);
  }
}

}  // namespace

double repose_angle(std::span<const double> x, std::span<const double> h, double layer, double* rms) {
  const size_t n = std::min(x.size(), h.size());
  if (n == 0) return std::nan("");
  const size_t peak = static_cast<size_t>(std::max_element(h.begin(), h.begin() + n) - h.begin());
  const double top = h[peak];
  const double toe = std::max(0.2 * top, 1.5 * layer);  // where the heap ends
  size_t end = peak;
  while (end < n && h[end] >= toe) ++end;
  std::vector<double> xs, hs;
  for (size_t k = peak; k < end; ++k)
    if (h[k] <= 0.8 * top) {
      xs.push_back(x[k]);
      hs.push_back(h[k]);
    }
  if (xs.size() < 3) return std::nan("");
  const LineFit f = fit_line(xs, hs);
  if (rms) {
    double s = 0;
    for (size_t k = 0; k < xs.size(); ++k) s += std::pow(hs[k] - (f.intercept + f.slope * xs[k]), 2);
    *rms = std::sqrt(s / xs.size());
  }
  return std::atan(-f.slope) * 180 / std::numbers::pi;
}

ShapeResult run_shape_case(const ShapePreset& preset, const ShapeCase& c,
                           const std::shared_ptr<Device>& device, const ShapeLog& log) {
  const auto t0 = std::chrono::steady_clock::now();
  ShapeResult r;
  r.shape = c;
  const Scene scene = column(preset, c);
  r.fidelity = scene.grains[0].origin;
  const auto say = [&](const std::string& m) {
    if (log) log(c.label + ": " + m);
  };
  r.repose = run_repose(preset, scene, device, say);
  if (preset.shear) run_shear(preset, c, device, say, r);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace simsols
