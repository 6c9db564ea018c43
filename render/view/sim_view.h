// SimulationView: what the renderer draws of a running Simulation.
//
// Glue between the solver and the renderer, one per (GL context,
// simulation): the ViewPacker (device kernels), the GL buffers, the
// ParticleBridge that fills them (shared or host copy), and the apparatus:
// every rectangle wall at its current position as a translucent plate, and
// plane walls as plates spanning the specimen. Everything is in the render
// frame, i.e. relative to the packer's origin, so float vertex data keeps
// its precision at the specimen wherever the scene sits.
//
// Colouring: `layer` uses the categorical map (one colour per layer band;
// shear-box specimens built in layers get their own layer spacing), `grain`
// the qualitative map (each grain, a clump or a free sphere, in a colour
// hashed from its number), the other fields the sequential map over their
// current range, unless the caller fixes a range.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/plot/colormap.h"
#include "render/view/particle_bridge.h"
#include "render/gl/renderer.h"
#include "render/view/view_pack.h"

namespace simsols::render {

plot::ColorMap colormap_for(ColorField field);
// "speed (m/s)", "layer", "contacts", ...
std::string legend_title(ColorField field);
// The legend's line under the scale: "one colour per grain" for grain, else empty.
std::string legend_note(ColorField field);

class SimulationView {
 public:
  SimulationView(const Gl& gl, Simulation& sim);

  ViewPacker& packer() { return packer_; }
  const ParticleBridge& bridge() const { return *bridge_; }

  struct Update {
    ViewPacker::Range range;
    ViewPacker::ContactStats contacts;
  };
  // Packs the current state: beads coloured by `field`, and the contacts
  // when `contacts` is set (else none are drawn).
  Update update(ColorField field, bool contacts);

  // The geometry to draw: the buffers, the walls where they are now, bounds.
  FrameGeometry geometry();
  // Bounds of the specimen and the apparatus (render frame): what camera
  // fitting uses, taken at the start and again only on refit_bounds() (the
  // lab calls it when a stage ends and on F), so a view does not jump as the
  // run goes on. The walls are drawn within half the specimen's size of it.
  glm::dvec3 lo() const { return lo_; }
  glm::dvec3 hi() const { return hi_; }
  void refit_bounds();  // the beads and walls where they are now

 private:
  void add_cell_faces(FrameGeometry& g, const glm::dvec3& origin);
  void set_bounds(const std::vector<Vec3>& centres, const std::vector<double>& radii,
                  const std::vector<Vec3>& wall_at);
  Simulation& sim_;
  ViewPacker packer_;
  GeometryBuffers buffers_;
  std::unique_ptr<ParticleBridge> bridge_;
  glm::dvec3 lo_{0}, hi_{0};
  // Rectangles are drawn within this box (relative to the origin, as lo_):
  // the specimen and half its size around it.
  glm::dvec3 clip_lo_{-1e300}, clip_hi_{1e300};
};

}  // namespace simsols::render
