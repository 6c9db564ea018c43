#include "render/view/sim_view.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "solver/core/observe.h"

namespace simsols::render {

plot::ColorMap colormap_for(ColorField field) {
  switch (field) {
    case ColorField::Layer: return plot::ColorMap::Categorical;
    case ColorField::Grain: return plot::ColorMap::Qualitative;
    default: return plot::ColorMap::Sequential;
  }
}

std::string legend_note(ColorField field) {
  return field == ColorField::Grain ? "one colour per grain" : "";
}

std::string legend_title(ColorField field) {
  const std::string unit = unit_of(field);
  return std::string(to_string(field)) + (unit.empty() ? "" : " (" + unit + ")");
}

namespace {

glm::dvec3 to_glm(const Vec3& v) { return {v[0], v[1], v[2]}; }

// An axis-aligned half extent `h` about `c` clipped to [lo, hi] along its
// axis (a rectangle's edge on one of x, y, z); other directions unchanged.
void clip_extent(glm::dvec3& c, glm::dvec3& h, const glm::dvec3& lo, const glm::dvec3& hi) {
  int axis = -1;
  for (int k = 0; k < 3; ++k)
    if (std::abs(h[k]) > 0) axis = axis < 0 ? k : 3;  // 3: not axis-aligned
  if (axis < 0 || axis > 2) return;
  const double a = std::max(c[axis] - std::abs(h[axis]), lo[axis]);
  const double b = std::min(c[axis] + std::abs(h[axis]), hi[axis]);
  if (b <= a) return;
  c[axis] = 0.5 * (a + b);
  h[axis] = (h[axis] < 0 ? -0.5 : 0.5) * (b - a);
}

// Two unit vectors spanning the plane normal to n.
std::pair<glm::dvec3, glm::dvec3> plane_axes(const glm::dvec3& n) {
  const glm::dvec3 a = std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(n, a));
  return {u, glm::cross(n, u)};
}

}  // namespace

SimulationView::SimulationView(const Gl& gl, Simulation& sim)
    : sim_(sim), packer_(sim), buffers_(gl) {
  const Scene& scene = sim.scene();
  // Layered specimens: one band per layer, from the reference heights (the
  // layers' centres are evenly spaced by construction).
  const Specimen* specimen = scene.specimen();
  if (specimen && specimen->method == Specimen::Method::Layers && specimen->layers > 1 &&
      !scene.particles.empty()) {
    double zmin = 1e300, zmax = -1e300;
    for (const Particle& p : scene.particles) {
      zmin = std::min(zmin, p.position[2]);
      zmax = std::max(zmax, p.position[2]);
    }
    const int layers = specimen->layers;
    if (zmax > zmin) packer_.set_layer_bands(zmin, (zmax - zmin) / (layers - 1));
  }
  std::vector<Vec3> centres, walls;
  std::vector<double> radii;
  for (const Particle& p : scene.particles) {
    centres.push_back(p.position);
    radii.push_back(p.radius);
  }
  for (const Wall& w : scene.walls) walls.push_back(w.point);
  set_bounds(centres, radii, walls);
  if (!radii.empty())  // the force chains' width scale
    buffers_.mutable_geometry().bead_radius =
        float(std::accumulate(radii.begin(), radii.end(), 0.0) / double(radii.size()));
  bridge_ = std::make_unique<ParticleBridge>(gl, buffers_, packer_, sim.model().device());
}

// Bounds: the specimen's beads (not a membrane's, which waits above the
// cell until it is wrapped about them) and the rectangles (walls at
// `wall_at`), these no further than half the specimen's size beyond it (the
// triaxial cell's plates are much larger than the specimen so they can
// slide past each other: the view frames the specimen, not them).
void SimulationView::set_bounds(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                                const std::vector<Vec3>& wall_at) {
  const Scene& scene = sim_.scene();
  const glm::dvec3 origin = to_glm(packer_.origin());
  glm::dvec3 lo(1e300), hi(-1e300);
  for (size_t i = 0; i < std::min(centres.size(), scene.specimen_count()); ++i) {
    lo = glm::min(lo, to_glm(centres[i]) - radii[i]);
    hi = glm::max(hi, to_glm(centres[i]) + radii[i]);
  }
  const bool beads = lo.x <= hi.x;
  const glm::dvec3 reach = beads ? 0.5 * (hi - lo) : glm::dvec3(1e300);
  const glm::dvec3 wall_lo = beads ? lo - reach : glm::dvec3(-1e300),
                   wall_hi = beads ? hi + reach : glm::dvec3(1e300);
  for (size_t i = 0; i < scene.walls.size(); ++i) {
    const Wall& w = scene.walls[i];
    if (w.shape != WallShape::Rectangle) continue;
    const glm::dvec3 c = to_glm(wall_at[i]), u = to_glm(w.axis_u) * w.half_u,
                     v = glm::cross(to_glm(w.normal), to_glm(w.axis_u)) * w.half_v;
    for (int k = 0; k < 4; ++k) {
      const glm::dvec3 q = glm::clamp(c + ((k & 1) ? u : -u) + ((k & 2) ? v : -v), wall_lo, wall_hi);
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
  }
  if (lo.x > hi.x) lo = hi = glm::dvec3(0);
  lo_ = lo - origin;
  hi_ = hi - origin;
  if (beads) {
    clip_lo_ = wall_lo - origin;
    clip_hi_ = wall_hi - origin;
  }
}

void SimulationView::refit_bounds() {
  const ParticleSnapshot s = sim_.snapshot();
  set_bounds(s.position, s.radius, wall_points(sim_.model(), sim_.state()));
}

SimulationView::Update SimulationView::update(ColorField field, bool contacts) {
  Update u;
  u.range = bridge_->update_beads(field);
  if (contacts) {
    u.contacts = bridge_->update_contacts(true);
  } else {
    buffers_.mutable_geometry().segment_count = 0;
  }
  return u;
}

FrameGeometry SimulationView::geometry() {
  FrameGeometry g = buffers_.geometry();
  const glm::dvec3 origin = to_glm(packer_.origin());
  const Scene& scene = sim_.scene();
  g.walls.clear();
  if (!scene.walls.empty()) {
    const std::vector<Vec3> points = wall_points(sim_.model(), sim_.state());
    const glm::dvec3 centre = 0.5 * (lo_ + hi_);
    const double span = 0.6 * glm::length(hi_ - lo_);
    for (size_t i = 0; i < scene.walls.size(); ++i) {
      const Wall& w = scene.walls[i];
      const glm::dvec3 p = to_glm(points[i]) - origin, n = to_glm(w.normal);
      WallQuad q;
      if (w.shape == WallShape::Rectangle) {
        // a tilting wall (a turned cap) as it stands
        const Wall now = w.tilts ? tilted_wall(w, sim_.wall_tilt(static_cast<int>(i)).angle) : w;
        const glm::dvec3 axis_u = to_glm(now.axis_u);
        glm::dvec3 c = p, u = axis_u * w.half_u, v = glm::cross(to_glm(now.normal), axis_u) * w.half_v;
        clip_extent(c, u, clip_lo_, clip_hi_);
        clip_extent(c, v, clip_lo_, clip_hi_);
        q.centre = glm::vec3(c);
        q.axis_u = glm::vec3(u);
        q.axis_v = glm::vec3(v);
      } else {
        // an infinite plane: the part of it under the specimen
        const auto [u, v] = plane_axes(n);
        q.centre = glm::vec3(centre - glm::dot(centre - p, n) * n);
        q.axis_u = glm::vec3(u * span);
        q.axis_v = glm::vec3(v * span);
      }
      g.walls.push_back(q);
    }
  }
  if (scene.periodic) add_cell_faces(g, origin);
  g.lo = lo_;
  g.hi = hi_;
  return g;
}

// A periodic cell's six faces, drawn as the walls are (translucent): the
// parallelogram faces of the cell as it stands, its images not drawn.
void SimulationView::add_cell_faces(FrameGeometry& g, const glm::dvec3& origin) {
  const CellNow& c = sim_.state().cell_now;
  const glm::dvec3 a(c.h[0], c.h[3], c.h[6]), b(c.h[1], c.h[4], c.h[7]), e(c.h[2], c.h[5], c.h[8]);
  const glm::dvec3 corner = to_glm(c.corner) + to_glm(sim_.model().origin()) - origin;
  const glm::dvec3 centre = corner + 0.5 * (a + b + e);
  const glm::dvec3 edges[3] = {a, b, e};
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 n = edges[k], u = edges[(k + 1) % 3], v = edges[(k + 2) % 3];
    for (double side : {-0.5, 0.5}) {
      WallQuad q;
      q.centre = glm::vec3(centre + side * n);
      q.axis_u = glm::vec3(0.5 * u);
      q.axis_v = glm::vec3(0.5 * v);
      g.walls.push_back(q);
    }
  }
}

}  // namespace simsols::render
