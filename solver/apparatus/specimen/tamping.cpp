#include "solver/apparatus/specimen/tamping.h"
#include "solver/apparatus/specimen/tamping_state.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "solver/apparatus/specimen/preparation.h"
#include "solver/apparatus/specimen/prep_log.h"
#include "solver/common/errors.h"
#include "solver/common/line_fit.h"
#include "solver/common/number_text.h"
#include "solver/common/atomic_file.h"
#include "solver/apparatus/registry.h"
#include "solver/apparatus/cell/stage_checks.h"
#include "solver/scene/clump.h"

namespace simsols {
namespace {

using Log = PrepLog;

// A platen that reaches its target pushing less than this found the layer
// already denser than aimed: tamping compacts, it cannot loosen.
constexpr double kLooseLayerStress = 1e3;  // Pa
constexpr double kLiftSlower = 10;  // the platen rises this much slower than it came down

constexpr const char* kLooseLayerNote =
    " (the layer settled denser than aimed, and tamping cannot loosen it: a higher "
    "specimen.preparation.friction settles the layers looser)";

// One grain of the poured column: a clump or a free bead, and how low it
// reaches.
struct ColumnGrain {
  double bottom = 0;
  int clump = -1;  // index into the column's clumps, or -1
  int particle = -1;
};

std::vector<ColumnGrain> column_grains(const Scene& column) {
  std::vector<ColumnGrain> g;
  for (size_t c = 0; c < column.clumps.size(); ++c) {
    const Clump& k = column.clumps[c];
    double bottom = k.position[2];
    for (int i = k.first; i < k.first + k.count; ++i)
      bottom = std::min(bottom, column.particles[i].position[2] - column.particles[i].radius);
    g.push_back({bottom, static_cast<int>(c), -1});
  }
  for (size_t i = 0; i < column.particles.size(); ++i)
    if (column.particles[i].clump < 0)
      g.push_back({column.particles[i].position[2] - column.particles[i].radius, -1, static_cast<int>(i)});
  std::sort(g.begin(), g.end(), [](const ColumnGrain& a, const ColumnGrain& b) { return a.bottom < b.bottom; });
  return g;
}

// Adds grains [from, to) of the column to `scene`, lowered so the lowest
// starts `gap` above `floor`; returns their solid volume.
double add_layer(Scene& scene, const Scene& column, const std::vector<GrainBody>& bodies,
                 const std::vector<ColumnGrain>& grains, size_t from, size_t to, double floor, double gap) {
  const double dz = floor + gap - grains[from].bottom;
  const std::vector<double> solid = solid_volumes(column);
  double volume = 0;
  for (size_t k = from; k < to; ++k) {
    if (grains[k].clump >= 0) {
      Clump c = column.clumps[grains[k].clump];
      c.position[2] += dz;
      for (int i = c.first; i < c.first + c.count; ++i) volume += solid[i];
      add_clump(scene, c, bodies[c.grain]);
    } else {
      Particle p = column.particles[grains[k].particle];
      p.position[2] += dz;
      volume += solid[grains[k].particle];
      scene.particles.push_back(p);
    }
  }
  return volume;
}

// The specimen as it lies now, at rest: beads and clumps rebuilt from the
// device's state (a clump's grain frame from its body frame).
Scene at_rest(const Scene& empty, const std::vector<GrainBody>& bodies, Simulation& sim) {
  Scene s = empty;
  const ParticleSnapshot snap = sim.snapshot();
  const std::vector<ClumpState> clumps = sim.scene().clumps.empty() ? std::vector<ClumpState>{} : sim.clumps();
  const Scene& was = sim.scene();
  for (size_t c = 0; c < was.clumps.size(); ++c) {
    Clump k = was.clumps[c];
    const GrainBody& body = bodies[k.grain];
    const Quaternion& t = body.to_grain;
    k.position = clumps[c].position;
    k.orientation = quat_multiply(clumps[c].orientation, {t[0], -t[1], -t[2], -t[3]});
    k.velocity = k.angular_velocity = {};
    add_clump(s, k, body);
  }
  for (size_t i = 0; i < was.particles.size(); ++i) {
    if (was.particles[i].clump >= 0) continue;
    Particle p = was.particles[i];
    p.position = snap.position[i];
    p.velocity = p.angular_velocity = {};
    s.particles.push_back(p);
  }
  return s;
}

// Stops every wall where it is. A settled test starts its consolidation
// at once (a triaxial cell's side plates then press the specimen on their
// servos): tamping is done in a still mould.
void hold_walls(Simulation& sim) {
  const std::vector<Wall>& walls = sim.scene().walls;
  for (int w = 0; w < static_cast<int>(walls.size()); ++w) {
    if (walls[w].servo.enabled) sim.set_servo(w, WallServo{});
    sim.set_wall_velocity(w, {0, 0, 0});
  }
}

// Raises the platen at kTampSpeed / kLiftSlower until it no longer
// touches the grains (or is back at `start`), `chunk` steps at a time. A
// tamper lifted at once releases the packing's elastic energy at once and
// throws grains up; unloaded slowly, the layer stays where it was tamped.
void unload(Simulation& sim, int platen, double start, std::int64_t chunk) {
  sim.set_wall_velocity(platen, {0, 0, kTampSpeed / kLiftSlower});
  while (sim.wall_reactions()[platen].force[2] != 0 && sim.wall_point(platen)[2] < start) sim.advance(chunk);
  sim.set_wall_velocity(platen, {0, 0, 0});
}

// Lets the layer settle, then brings the platen down from just above the
// grains at kTampSpeed until it reaches `target` or pushes with
// kTampStress, lifts it off slowly and lets the grains come to rest. `say`
// takes a progress line every 10 s.
void tamp(Simulation& sim, LoadingProgramme& test, double target, double area, TampedLayer& out,
          const Log& say) {
  Ticker ticker;
  const auto tell = [&](const char* what) {
    say.check();
    if (!ticker.due()) return;
    char line[160];
    std::snprintf(line, sizeof line, "layer %d: %s, t = %.4f s, step %lld, %.0f s", out.layer, what,
                  sim.time(), static_cast<long long>(sim.steps()), ticker.elapsed());
    say(line);
  };
  test.advance(1);
  while (!test.done() && std::string(test.stage_name()) == "settle") {
    test.advance(2000);
    tell("settling");
  }
  hold_walls(sim);
  const int platen = platen_wall(sim.scene());
  const Vec3 park = sim.wall_point(platen);
  const double top = specimen_top(sim);
  const double start = std::max(top, target) + 1e-4;
  sim.set_servo(platen, WallServo{});  // moved by velocity alone
  sim.set_wall_point(platen, {park[0], park[1], start});
  sim.set_wall_velocity(platen, {0, 0, -kTampSpeed});
  const std::int64_t chunk = std::max<std::int64_t>(1, std::llround(2e-5 / kTampSpeed / sim.dt()));
  const double longest = 2 * (start - target) / kTampSpeed + 0.01;  // s, in case it stalls
  const double t0 = sim.time();
  for (;;) {
    sim.advance(chunk);
    const double z = sim.wall_point(platen)[2], push = std::abs(sim.wall_reactions()[platen].force[2]) / area;
    out.platen_stop = z, out.stress = push;
    if (z <= target || push >= kTampStress || sim.time() - t0 > longest) break;
    tell("tamping");
  }
  sim.set_wall_velocity(platen, {0, 0, 0});
  sim.advance(chunk * 20);  // held a moment
  unload(sim, platen, start, chunk * kLiftSlower);
  sim.set_wall_point(platen, park);
  const std::int64_t rest = std::llround(0.02 / sim.dt());  // the lifted layer springs back and rests
  sim.advance(rest);
}

// After layer k of n, whose wall times so far are `seconds` (one per
// layer): the time so far and an estimate of the rest. A layer settles
// and is tamped with every grain below it in the simulation, so its cost
// grows with j: the rest follows the least-squares line through the
// layers' times (its slope at least 0), or the first layer's time alone.
std::string layers_time(int n, const std::vector<double>& seconds) {
  const int k = static_cast<int>(seconds.size());
  double elapsed = 0;
  for (double t : seconds) elapsed += t;
  char buf[96];
  if (k >= n) {
    std::snprintf(buf, sizeof buf, "; %.0f s", elapsed);
    return buf;
  }
  std::vector<double> layer(k);
  for (int j = 0; j < k; ++j) layer[j] = j + 1;
  const LineFit f = fit_line(layer, seconds);
  const double slope = f.fitted ? std::max(0.0, f.slope) : 0;
  const double at_mean = elapsed / k, mean_layer = (k + 1) / 2.0;
  double left = 0;
  for (int j = k + 1; j <= n; ++j) left += std::max(0.0, at_mean + slope * (j - mean_layer));
  std::snprintf(buf, sizeof buf, "; %.0f s in, about %.0f s to go", elapsed, left);
  return buf;
}

}  // namespace

double layer_void_ratio(double e, double undercompaction, int j, int n) {
  const double u = n > 1 ? undercompaction * (n - j) / (n - 1) : 0;
  return (1 + e) / (1 - u) - 1;
}

std::string tamping_csv(const std::vector<TampedLayer>& layers) {
  std::ostringstream o;
  o << "layer,grains,target_void_ratio,target_top_m,platen_stop_m,platen_stress_Pa,void_ratio\n";
  for (const TampedLayer& l : layers)
    o << l.layer << ',' << l.grains << ',' << shortest_number(l.target_void_ratio) << ','
      << shortest_number(l.target_top) << ',' << shortest_number(l.platen_stop) << ','
      << shortest_number(l.stress) << ',' << shortest_number(l.void_ratio) << '\n';
  return o.str();
}

bool tamp_specimen(Scene& scene, const std::shared_ptr<Device>& device, double void_ratio,
                   const std::filesystem::path& out_dir, const Log& log) {
  Specimen* specimen = scene.specimen();
  if (!specimen || specimen->preparation.tamping_layers <= 0) return false;
  const Preparation prep = specimen->preparation;
  const int n = prep.tamping_layers;
  const double area = scene.cell()->length * scene.cell()->width;
  const std::vector<ColumnGrain> grains = column_grains(scene);
  Scene empty = scene;
  empty.particles.clear();
  empty.clumps.clear();
  Scene built = empty;
  std::vector<GrainBody> bodies;  // the unit bodies, once per grain (add_clump scales them)
  for (const Grain& g : scene.grains) bodies.push_back(grain_body(g));
  // a tamping stopped between layers goes on from the last one done
  const std::filesystem::path state_file = out_dir / kTampingStateFile;
  TampingState st;
  st.key = tamping_key(scene, void_ratio);
  const bool keep = !out_dir.empty();
  if (std::optional<TampingState> was = keep ? load_tamping_state(state_file, st.key) : std::nullopt) {
    st = std::move(*was);
    for (const Clump& c : st.clumps) add_clump(built, c, bodies[c.grain]);
    built.particles.insert(built.particles.end(), st.spheres.begin(), st.spheres.end());
    log("going on after layer " + std::to_string(st.layers.size()) + " of " + std::to_string(n) +
        " (" + state_file.string() + ")");
  }
  std::vector<TampedLayer>& layers = st.layers;
  double& floor = st.floor;
  double& solid_total = st.solid_total;
  std::vector<double>& seconds = st.seconds;  // wall time per layer
  for (int k = static_cast<int>(layers.size()) + 1; k <= n; ++k) {
    const Ticker clock;
    const size_t from = grains.size() * (k - 1) / n, to = grains.size() * k / n;
    TampedLayer l;
    l.layer = k;
    l.grains = static_cast<int>(to - from);
    l.target_void_ratio = layer_void_ratio(void_ratio, prep.undercompaction, k, n);
    const double solid = add_layer(built, scene, bodies, grains, from, to, floor, 1e-4);
    // the layers below at the target (this one's tamping compacts them to it), this one looser
    l.target_top = (solid_total * (1 + void_ratio) + solid * (1 + l.target_void_ratio)) / area;
    solid_total += solid;
    Simulation sim(device, built);
    const std::unique_ptr<ApparatusProgramme> test = make_programme(sim);
    tamp(sim, *test, l.target_top, area, l, log);
    l.void_ratio = measure_specimen(sim).bulk_void_ratio;
    floor = specimen_top(sim);
    built = at_rest(empty, bodies, sim);
    layers.push_back(l);
    char line[200];
    std::snprintf(line, sizeof line,
                  "layer %d of %d: %d grains, e_j %.4f, platen stopped at %.3f mm (target %.3f mm, %.0f kPa); e %.4f",
                  k, n, l.grains, l.target_void_ratio, 1e3 * l.platen_stop, 1e3 * l.target_top,
                  l.stress / 1e3, l.void_ratio);
    seconds.push_back(clock.elapsed());
    st.clumps = built.clumps;
    st.spheres.clear();
    for (const Particle& p : built.particles)
      if (p.clump < 0) st.spheres.push_back(p);
    if (keep) {
      std::filesystem::create_directories(out_dir);
      save_tamping_state(state_file, st);
    }
    log(std::string(line) + (l.stress < kLooseLayerStress ? kLooseLayerNote : "") +
        layers_time(n, seconds));
  }
  char done[200];
  std::snprintf(done, sizeof done,
                "tamped: e = %.4f at the platen's last stop, %.3f mm (aimed %.4f); unloaded, %.4f to the "
                "highest grain's top at %.3f mm",
                area * layers.back().platen_stop / solid_total - 1, 1e3 * layers.back().platen_stop, void_ratio,
                layers.back().void_ratio, 1e3 * floor);
  log(done);
  if (const auto check = required_apparatus_kind(built).check_specimen_top)
    if (std::optional<SceneIssue> issue = check(built, floor))
      throw SceneError(issue->code, scene.source_path, 0, issue->field, issue->message);
  Specimen& s = *built.specimen();
  s.method = Specimen::Method::Given;
  s.preparation.tamping_layers = 0;
  s.preparation.void_ratio.reset();
  s.preparation.relative_density.reset();
  scene = built;
  std::filesystem::create_directories(out_dir);
  write_file_atomic((out_dir / "tamping.csv").string(), tamping_csv(layers));
  if (keep) std::filesystem::remove(state_file);
  return true;
}

}  // namespace simsols
