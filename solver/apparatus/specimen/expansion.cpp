#include "solver/apparatus/specimen/expansion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include "solver/apparatus/specimen/preparation.h"
#include "solver/apparatus/specimen/prep_log.h"
#include "solver/apparatus/registry.h"
#include "solver/apparatus/cell/stage_checks.h"
#include "solver/common/errors.h"
#include "solver/scene/sphere_grid.h"

namespace simsols {
namespace {

using Log = PrepLog;

// Solid fraction the cell would hold at full size below the lid's start:
// denser than a frictional packing of spheres, so the grown beads meet the
// lid and push it up, unless they are graded widely enough to pack denser.
constexpr double kLidFraction = 0.64;

struct Cell {
  double length, width, height;
};

// The beads at kStartScale of their radii, at random without overlap in
// the cell below the lid (largest first), at rest.
void place_shrunk(Scene& x, const Cell& c, std::int64_t seed, const std::string& file,
                  const std::string& table) {
  std::vector<size_t> order(x.particles.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return x.particles[a].radius > x.particles[b].radius; });
  const double r_max = kStartScale * x.particles[order.front()].radius;
  SphereGrid grid(2 * r_max, order.size());
  std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
  const auto uniform = [&](double a, double b) {
    return a + (b - a) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
  };
  const std::int64_t budget = 1000 + 5000LL * static_cast<std::int64_t>(order.size());
  std::int64_t attempts = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    Particle& p = x.particles[order[k]];
    p.radius *= kStartScale;
    p.velocity = p.angular_velocity = {};
    bool hit = true;
    while (hit) {
      if (attempts++ == budget)
        throw SceneError("out_of_range", file, 0, table + ".specimen.preparation.expansion",
                         "could place only " + std::to_string(k) + " of " + std::to_string(order.size()) +
                             " beads at " + std::to_string(int(kStartScale * 100)) +
                             " % of their size in the cell: the grading is too wide to grow from there");
      p.position = {uniform(p.radius, c.length - p.radius), uniform(p.radius, c.width - p.radius),
                    uniform(p.radius, c.height - p.radius)};
      hit = false;
      grid.for_each_near(p.position, [&](int q) {
        const Particle& o = x.particles[order[q]];
        const Vec3 d{p.position[0] - o.position[0], p.position[1] - o.position[1],
                     p.position[2] - o.position[2]};
        const double reach = p.radius + o.radius;
        hit = hit || d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < reach * reach;
      });
    }
    grid.insert(static_cast<int>(k), p.position);
  }
}

// The scene the beads grow in: shrunk, placed, no gravity, no servo, a
// skin wide enough for the grid to hold the full-size beads.
Scene growth_scene(const Scene& scene, const Cell& c, double r_max) {
  Scene x = scene;
  const Specimen& s = *scene.specimen();
  const std::string table = apparatus_kind(scene)->name;
  place_shrunk(x, c, s.seed, scene.source_path, table);
  x.effects.gravity = {0, 0, 0};
  for (Wall& w : x.walls) w.servo.enabled = false;
  const double skin = x.numerics.skin > 0 ? x.numerics.skin : std::max(0.2 * r_max, 2 * x.rupture_distance());
  x.numerics.skin = skin + 2 * r_max * (1 - kStartScale);
  return x;
}

// The grown specimen as the scene's own: full radii, where the beads are,
// at rest, `given`.
Scene as_given(const Scene& scene, Simulation& sim) {
  Scene g = scene;
  const ParticleSnapshot snap = sim.snapshot();
  for (size_t i = 0; i < g.particles.size(); ++i) {
    g.particles[i].position = snap.position[i];
    g.particles[i].velocity = g.particles[i].angular_velocity = {};
  }
  Specimen& s = *g.specimen();
  s.method = Specimen::Method::Given;
  s.preparation.expansion = false;
  s.preparation.void_ratio.reset();
  s.preparation.relative_density.reset();
  return g;
}

}  // namespace

Expansion expand_specimen(const Scene& scene, const std::shared_ptr<Device>& device, const Log& log) {
  const ApparatusCell& cell = *scene.cell();
  const Specimen& spec = cell.specimen;
  const double area = cell.length * cell.width;
  double solid = 0, r_max = 0;
  for (const Particle& p : scene.particles) {
    solid += 4.0 / 3.0 * M_PI * p.radius * p.radius * p.radius;
    r_max = std::max(r_max, p.radius);
  }
  const Cell c{cell.length, cell.width, solid / (kLidFraction * area)};
  Simulation sim(device, growth_scene(scene, c, r_max));
  preparation_friction(sim, spec, true);
  const int lid = platen_wall(sim.scene());
  const Vec3 park = sim.wall_point(lid);
  sim.set_wall_point(lid, {park[0], park[1], c.height});
  const double wave = std::sqrt(kExpansionStress / scene.materials[spec.material].density);  // m/s
  const std::int64_t chunk = 50;
  double s = kStartScale, rested = 0, sigma = 0;
  bool carried = false;
  Ticker ticker;
  while (rested < kRestTime) {
    sigma = std::abs(sim.wall_reactions()[lid].force[2]) / area;
    carried = carried || sigma >= 0.5 * kExpansionStress;
    const double rate = (carried ? kGrowthInertia : kCloudInertia) * wave / spec.diameter;  // 1/s
    const double next = std::min(1.0, s + rate * chunk * sim.dt());
    if (next > s) sim.scale_radii(next / s);
    if (s == 1) rested += chunk * sim.dt();
    s = next;
    const double height = sim.wall_point(lid)[2];
    const double v_max = std::min(4 * rate * height, 0.1 * wave);
    const double v = -v_max * std::clamp(1 - sigma / kExpansionStress, -1.0, 1.0);
    sim.set_wall_velocity(lid, {0, 0, v});
    sim.advance(chunk);
    log.check();
    if (!ticker.due()) continue;
    char line[200];
    std::snprintf(line, sizeof line, "growing: %.2f %% of full size, lid at %.3f mm pushing %.1f kPa, t = %.4f s, step %lld, %.0f s",
                  100 * s, 1e3 * height, sigma / 1e3, sim.time(), static_cast<long long>(sim.steps()),
                  ticker.elapsed());
    log(line);
  }
  Expansion e;
  e.grown = as_given(scene, sim);
  e.seconds = sim.time();
  e.steps = sim.steps();
  e.lid_height = sim.wall_point(lid)[2];
  e.lid_stress = sigma;
  return e;
}

}  // namespace simsols
