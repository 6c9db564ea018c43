#include "solver/apparatus/specimen/specimen.h"

#include "solver/apparatus/cell/cell_walls.h"
#include "solver/apparatus/specimen/grading.h"
#include "solver/scene/clump.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>

#include "solver/common/number_text.h"
#include "solver/scene/sphere_grid.h"

namespace simsols {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double v) { return shortest_number(v); }

// The cell's footprint and the checks of the apparatus table it belongs to.
struct Cell {
  double length, width;
  TableCheck check;
};

// Seeded and identical on every platform (mt19937_64 is fully specified).
class Prng {
 public:
  explicit Prng(std::uint64_t seed) : engine_(seed) {}
  double uniform(double a, double b) {
    return a + (b - a) * (static_cast<double>(engine_() >> 11) * 0x1.0p-53);
  }

 private:
  std::mt19937_64 engine_;
};

// The paper's preparation: square layers, clearance shifted or spread.
void place_layers(Scene& scene, const Specimen& s, const Cell& b) {
  const double d = s.diameter, r = d / 2;
  const LayerGrid grid = layer_grid(b.length, b.width, d);
  const double pitch = grid.pitch;
  const int nx = grid.nx, ny = grid.ny;
  const double cx = b.length - nx * pitch, cy = b.width - ny * pitch;  // clearances
  Prng prng(static_cast<std::uint64_t>(s.seed));
  for (int k = 0; k < s.layers; ++k) {
    const double z = r + k * d * 1.001;
    double sx = 0, sy = 0, gx = 0, gy = 0;  // layer shift; gap between rows
    if (s.clearance == Specimen::Clearance::Shift) {
      sx = prng.uniform(0, cx);
      sy = prng.uniform(0, cy);
    } else {
      gx = cx / (nx + 1);
      gy = cy / (ny + 1);
      sx = gx;
      sy = gy;
    }
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        scene.particles.push_back({s.material, r,
                                   {sx + r + i * (pitch + gx), sy + r + j * (pitch + gy), z},
                                   {},
                                   {}});
  }
}

// The pour's diameters, largest first: as many beads of d as the layers
// would hold, or with a grading, sizes drawn from its curve until they
// hold the same solid volume (the layers of D50 beads; grading.h).
std::vector<double> pour_sizes(const Specimen& s, const Cell& b) {
  const double d = s.diameter;
  const int count = beads_per_layer(b.length, b.width, d) * s.layers;
  if (s.grading.law == Grading::Law::Single) return std::vector<double>(count, d);
  const GradingCurve curve = grading_curve(s.grading, d);
  const double largest = curve.size.back(), side = std::min(b.length, b.width);
  if (largest > side)
    b.check.fail("out_of_range", "specimen.grading.d_max",
                 num(largest) + " m does not fit the cell, allowed (0, " + num(side) + "] m");
  const double smallest = curve.size.front(), solid = count * kPi / 6 * d * d * d;
  if (solid / (kPi / 6 * smallest * smallest * smallest) > 2e7 * 50)
    b.check.fail("out_of_range", "specimen.grading.d_min",
                 "the grading's fines would make far more than 2e7 beads; raise d_min");
  std::vector<double> sizes = sample_diameters(curve, solid, static_cast<std::uint64_t>(s.seed) ^ 0x9e3779b97f4a7c15ULL);
  if (sizes.size() > 20000000)
    b.check.fail("out_of_range", "specimen.grading",
                 "the specimen would hold " + std::to_string(sizes.size()) + " beads (limit 2e7)");
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  return sizes;
}

// The pouring column's height: three specimen heights, or the height at
// which the beads fill the preparation's intensity (its solid fraction).
double column_height(const Specimen& s, const Cell& b, const std::vector<double>& sizes) {
  if (s.preparation.intensity <= 0) return 3.0 * s.layers * s.diameter;
  double solid = 0;
  for (double d : sizes) solid += kPi / 6 * d * d * d;
  return std::max(solid / (s.preparation.intensity * b.length * b.width), 1.5 * sizes.front());
}

// The rain's speed: that of a free fall from the preparation's drop height.
Vec3 rain_velocity(const Scene& scene, const Specimen& s, const Cell& b) {
  const double h = s.preparation.drop_height;
  if (h <= 0) return {};
  const double g = norm(scene.effects.gravity);
  if (!(g > 0))
    b.check.fail("conflicting_keys", "specimen.preparation.drop_height",
                 "a drop height needs gravity (effects.gravity is zero)");
  const double v = std::sqrt(2 * g * h);
  const Vec3& down = scene.effects.gravity;
  return {v * down[0] / g, v * down[1] / g, v * down[2] / g};
}

// Random pour: the beads placed at random, without overlap, largest first,
// in the pouring column, raining at the drop height's speed.
void place_pour(Scene& scene, const Specimen& s, const Cell& b) {
  const std::vector<double> sizes = pour_sizes(s, b);
  const int count = static_cast<int>(sizes.size());
  const double top = column_height(s, b, sizes), d_max = sizes.front();
  const Vec3 rain = rain_velocity(scene, s, b);
  Prng prng(static_cast<std::uint64_t>(s.seed));
  // cells one mean diameter wide, each bead's test as wide as it may touch
  double d_mean = 0;
  for (double d : sizes) d_mean += d / count;
  SphereGrid grid(d_mean, static_cast<size_t>(count), {0, 0, 0}, {b.length, b.width, top});
  std::vector<std::array<double, 4>> beads;  // centre and radius, packed for the tests
  beads.reserve(static_cast<size_t>(count));
  const std::int64_t budget = 1000 + 2000LL * count;
  std::int64_t attempts = 0;
  for (int placed = 0; placed < count; ++placed) {
    const double r = sizes[placed] / 2;
    Vec3 p{};
    bool hit = true;
    while (hit) {
      if (attempts++ == budget)
        b.check.fail("out_of_range", "specimen.layers",
             "could place only " + std::to_string(placed) + " of " + std::to_string(count) +
                 " beads in the pouring column; use fewer layers");
      p = {prng.uniform(r, b.length - r), prng.uniform(r, b.width - r),
           prng.uniform(r, top - r)};
      hit = grid.any_within(p, r + d_max / 2, [&](int q) {
        const std::array<double, 4>& o = beads[static_cast<size_t>(q)];
        const double dx = p[0] - o[0], dy = p[1] - o[1], dz = p[2] - o[2], reach = r + o[3];
        return dx * dx + dy * dy + dz * dz < reach * reach;
      });
    }
    grid.insert(placed, p);
    beads.push_back({p[0], p[1], p[2], r});
    scene.particles.push_back({s.material, r, p, rain, {}});
  }
}

// A pour of clumps: the pour's sizes (pour_sizes: one per bead the
// layers would hold, or drawn from the grading) as the grains'
// volume-equivalent diameters, each grain scaled to its size; centroids
// placed at random in the pouring column (made taller when the grains'
// bounding spheres need it), largest first, with their bounding spheres
// apart; each turned uniformly at random; raining as the beads do.
void place_clump_pour(Scene& scene, const Specimen& s, const Cell& b) {
  const GrainBody body = grain_body(scene.grains[s.grain]);
  const double d_eq = volume_equivalent_diameter(body);
  double unit_reach = 0;  // the bounding sphere about the centroid, at scale 1
  for (size_t k = 0; k < body.offsets.size(); ++k)
    unit_reach = std::max(unit_reach, norm(body.offsets[k]) + body.radii[k]);
  const std::vector<double> sizes = pour_sizes(s, b);
  const double largest = unit_reach * sizes.front() / d_eq, side = std::min(b.length, b.width);
  if (2 * largest > side)
    b.check.fail("out_of_range", "specimen.grain",
                 "the largest grain spans " + num(2 * largest) + " m, more than the cell's " +
                     num(side) + " m");
  double bounding = 0;  // the bounding spheres fill at most a quarter of the column (RSA jams near 0.38)
  for (double d : sizes) bounding += 4 * kPi / 3 * std::pow(unit_reach * d / d_eq, 3);
  const double top = std::max(column_height(s, b, sizes), bounding / (0.25 * b.length * b.width));
  const Vec3 rain = rain_velocity(scene, s, b);
  Prng prng(static_cast<std::uint64_t>(s.seed));
  SphereGrid grid(2 * largest, sizes.size());
  std::vector<std::pair<Vec3, double>> placed;  // centroid, reach
  const std::int64_t budget = 1000 + 2000LL * static_cast<std::int64_t>(sizes.size());
  std::int64_t attempts = 0;
  while (placed.size() < sizes.size()) {
    const double scale = sizes[placed.size()] / d_eq, reach = unit_reach * scale;
    if (attempts++ == budget)
      b.check.fail("out_of_range", "specimen.layers",
                   "could place only " + std::to_string(placed.size()) + " of " +
                       std::to_string(sizes.size()) + " grains in the pouring column; use fewer layers");
    const Vec3 p = {prng.uniform(reach, b.length - reach), prng.uniform(reach, b.width - reach),
                    prng.uniform(reach, std::max(reach, top - reach))};
    bool hit = false;
    grid.for_each_near(p, [&](int q) {
      hit = hit || norm(sub(p, placed[q].first)) < reach + placed[q].second;
    });
    if (hit) continue;
    grid.insert(static_cast<int>(placed.size()), p);
    placed.push_back({p, reach});
    Clump c;
    c.grain = s.grain;
    c.scale = scale;
    c.material = s.material;
    c.position = p;
    // the grain's frame turned at random (body_orientation adds its principal frame)
    c.orientation = uniform_rotation(prng.uniform(0, 1), prng.uniform(0, 1), prng.uniform(0, 1));
    c.velocity = rain;
    add_clump(scene, c, body);
  }
}

// Checks the specimen's settings and places its beads.
void place_in(Scene& scene, const Specimen& s, const Cell& b) {
  if (s.method == Specimen::Method::Given) return;
  if (s.material < 0 || s.material >= static_cast<int>(scene.materials.size()))
    b.check.fail("unknown_material", "specimen.material", "the specimen's material does not exist");
  const double side = std::min(b.length, b.width);
  b.check.require(s.diameter > 0 && s.diameter <= side, "specimen.diameter", s.diameter,
          "(0, " + num(side) + "] m");
  b.check.require(s.layers >= 1 && s.layers <= 200, "specimen.layers", s.layers, "[1, 200]");
  const double beads = double(beads_per_layer(b.length, b.width, s.diameter)) * s.layers;
  if (beads > 2e7)
    b.check.fail("out_of_range", "specimen.diameter",
         "the specimen would hold " + num(beads) + " beads (limit 2e7)");
  if (!scene.particles.empty())
    b.check.fail("conflicting_keys", "specimen.method",
         "the scene lists particles; use specimen.method = \"given\" to shear them");
  if (s.method == Specimen::Method::Layers)
    place_layers(scene, s, b);
  else if (s.grain >= 0)
    place_clump_pour(scene, s, b);
  else
    place_pour(scene, s, b);
}

}  // namespace

LayerGrid layer_grid(double length, double width, double d) {
  LayerGrid g;
  g.pitch = d * (1 + 1e-6);
  g.nx = static_cast<int>(std::floor(length / g.pitch));
  g.ny = static_cast<int>(std::floor(width / g.pitch));
  return g;
}

int beads_per_layer(double length, double width, double d) {
  const LayerGrid g = layer_grid(length, width, d);
  return g.nx * g.ny;
}

std::optional<SceneIssue> place_specimen(Scene& scene, const Specimen& specimen,
                                         double length, double width, const std::string& table) {
  try {
    place_in(scene, specimen, Cell{length, width, TableCheck{table}});
  } catch (const TableProblem& p) {
    return p.issue;
  }
  return std::nullopt;
}

}  // namespace simsols
