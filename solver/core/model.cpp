#include "solver/core/model.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "solver/common/errors.h"
#include "solver/core/real_packer.h"

namespace simsols {
Model::Model(std::shared_ptr<Device> device, const Scene& scene)
    : device_(std::move(device)), scene_(scene) {
  if (!device_) throw DeviceError("Model: no OpenCL device given (Device::open opens one)");
  if (!scene_.placed())
    throw std::logic_error("Model: the scene '" + scene_.name +
                           "' is read but not placed (place_scene, solver/io/scene_toml.h)");
  if (scene_.particles.empty())
    throw SceneError("no_particles", scene_.source_path, 0, "particles", "the scene has no particles");
  program_ = std::make_unique<Program>(*device_, make_kernel_config(scene_, *device_));
  const Program& p = *program_;
  kernels_.grid_clear = p.kernel("grid_clear");
  kernels_.grid_count = p.kernel("grid_count");
  kernels_.wrap_positions = p.kernel("wrap_positions");
  kernels_.scan_chunks = p.kernel("scan_chunks");
  kernels_.scan_totals = p.kernel("scan_totals");
  kernels_.scan_apply = p.kernel("scan_apply");
  kernels_.grid_scatter = p.kernel("grid_scatter");
  kernels_.count_neighbors = p.kernel("count_neighbors");
  kernels_.slice_widths = p.kernel("slice_widths");
  kernels_.build_neighbors = p.kernel("build_neighbors");
  kernels_.build_mirrors = p.kernel("build_mirrors");
  kernels_.pair_forces = p.kernel("pair_forces");
  kernels_.finish_particles = p.kernel("finish_particles");
  kernels_.reduce_observables = p.kernel("reduce_observables");
  if (config().walls) {
    kernels_.advance_walls = p.kernel("advance_walls");
    kernels_.build_wall_near = p.kernel("build_wall_near");
    kernels_.wall_widths = p.kernel("wall_widths");
    kernels_.carry_wall_slots = p.kernel("carry_wall_slots");
    kernels_.reset_wall_travel = p.kernel("reset_wall_travel");
    kernels_.reduce_walls = p.kernel("reduce_walls");
  }
  if (config().servo) kernels_.servo_walls = p.kernel("servo_walls");
  if (config().clumps) kernels_.move_clumps = p.kernel("move_clumps");
  if (config().membrane) kernels_.membrane_forces = p.kernel("membrane_forces");

  rayleigh_dt_ = rayleigh_time_step(scene_);
  dt_ = effective_time_step(scene_);
  double rmax = 0;
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Particle& q : scene_.particles) {
    rmax = std::max(rmax, q.radius);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], q.position[a]);
      hi[a] = std::max(hi[a], q.position[a]);
    }
  }
  // with capillary bridges the lists must hold every pair within the rupture
  // distance: each bead moves < skin/4 between builds (validate_scene
  // refuses an explicit skin below twice the rupture distance)
  skin_ = scene_.numerics.skin > 0 ? scene_.numerics.skin
                                   : std::max(0.2 * rmax, 2 * scene_.rupture_distance());
  cell_size_ = 2 * rmax + skin_;
  // The float frame is centred on the initial packing, rounded to the largest
  // diameter: reproducible, and independent of numerics such as the skin
  // (the origin changes how positions round, hence results in the last bits).
  for (int a = 0; a < 3; ++a) origin_[a] = std::round(0.25 * (lo[a] + hi[a]) / rmax) * 2 * rmax;

  pairs_ = make_pair_table(scene_);
  const bool dbl = config().double_precision;
  const std::vector<unsigned char> packed = pack_pairs();
  pair_buf_ = device_->alloc(packed.size(), packed.data());

  RealPacker wk(dbl);
  for (const Wall& w : scene_.walls) {
    const Vec3 v = cross(w.normal, w.axis_u);
    wk.put4(w.point[0] - origin_[0], w.point[1] - origin_[1], w.point[2] - origin_[2],
             w.shape == WallShape::Plane ? 0 : 1);
    wk.put4(w.normal[0], w.normal[1], w.normal[2], w.material);
    wk.put4(w.axis_u[0], w.axis_u[1], w.axis_u[2], w.half_u);
    wk.put4(v[0], v[1], v[2], w.half_v);
  }
  wall_buf_ = device_->alloc(wk.bytes().size(), wk.bytes().data());
  const int asked = device_->options().local_size;
  if (!allowed_local_size(asked))
    throw DeviceError("EngineOptions::local_size (SIMSOLS_LOCAL_SIZE) must be a power of two "
                      "from 1 to 1024, not " + std::to_string(asked));
  local_size_ = static_cast<size_t>(asked);
  make_clumps();
}

void Model::make_clumps() {
  const Scene& s = scene_;
  const size_t n = s.particles.size();
  particle_mass_.resize(n);
  for (size_t i = 0; i < n; ++i) particle_mass_[i] = s.mass(s.particles[i]);
  for (const Grain& g : s.grains) grain_bodies_.push_back(grain_body(g));
  const bool dbl = config().double_precision;
  RealPacker inertia(dbl), offsets(dbl);
  // body: each particle's group (common.cl, HAS_GROUPS), a stand-in entry without one
  const bool groups = !s.clumps.empty() || s.membrane.count() > 0;
  std::vector<std::int32_t> members, body(groups ? n : 1, -1);
  for (int k = 0; k < s.membrane.count(); ++k)  // the membrane is the group after the clumps
    body[size_t(s.membrane.first + k)] = static_cast<std::int32_t>(s.clumps.size());
  std::vector<Vec3> offset(n, Vec3{});
  std::vector<double> body_mass = particle_mass_;  // a free sphere is its own body
  for (size_t c = 0; c < s.clumps.size(); ++c) {
    const Clump& k = s.clumps[c];
    const GrainBody b = scaled(grain_bodies_[k.grain], k.scale);
    const double rho = s.materials[k.material].density, mass = rho * b.mass.volume;
    double spheres = 0;
    for (double r : b.radii) spheres += r * r * r;
    for (int j = 0; j < k.count; ++j) {
      const size_t i = static_cast<size_t>(k.first + j);
      particle_mass_[i] = mass * b.radii[j] * b.radii[j] * b.radii[j] / spheres;
      body[i] = static_cast<std::int32_t>(c);
      offset[i] = b.offsets[j];
      body_mass[i] = mass;
    }
    inertia.put4(mass, rho * b.mass.principal[0], rho * b.mass.principal[1], rho * b.mass.principal[2]);
    members.push_back(k.first);
    members.push_back(k.count);
  }
  total_mass_ = 0;
  for (double m : particle_mass_) total_mass_ += m;
  if (s.clumps.empty()) {
    inertia.put4(0, 0, 0, 0);
    members = {0, 0};
    offsets.put4(0, 0, 0, 0);
  } else {
    for (size_t i = 0; i < n; ++i) offsets.put4(offset[i][0], offset[i][1], offset[i][2], body_mass[i]);
  }
  clump_buf_ = device_->alloc(inertia.bytes().size(), inertia.bytes().data());
  clump_member_buf_ = device_->alloc(members.size() * sizeof(std::int32_t), members.data());
  body_buf_ = device_->alloc(body.size() * sizeof(std::int32_t), body.data());
  body_offset_buf_ = device_->alloc(offsets.bytes().size(), offsets.bytes().data());
}

// The pair table as the kernels read it (contact_law.cl), in the slots of
// layout.h's PairSlot, with the friction override applied.
std::vector<unsigned char> Model::pack_pairs() const {
  RealPacker pk(config().double_precision);
  for (const PairCoefficients& c : pairs_.pairs) {
    const double mu_s = friction_ ? friction_->sliding.value_or(c.sliding_friction) : c.sliding_friction;
    const double mu_r = friction_ ? friction_->rolling.value_or(c.rolling_friction) : c.rolling_friction;
    static_assert(PAIR_E_STAR == 0 && PAIR_G_STAR == 1 && PAIR_GAMMA_N == 2 && PAIR_MU_S == 3 &&
                  PAIR_MU_R == 4 && PAIR_KT_RATIO == 5 && PAIR_RECORD_BASE == 8 &&
                  PAIR_CAP_TENSION == 8 && PAIR_CAP_VOLUME == 9 && PAIR_CAP_RUPTURE == 10 &&
                  PAIR_RECORD_CAPILLARY == 12, "the order put below");
    const double gamma_n = friction_ && friction_->restitution
                               ? damping_for_restitution(*friction_->restitution)
                               : c.gamma_n;
    pk.put4(c.e_star, c.g_star, gamma_n, mu_s);
    pk.put4(mu_r, std::sqrt(6 * c.g_star / c.e_star), 0, 0);
    if (config().capillary) pk.put4(c.capillary_tension, c.liquid_volume, c.rupture_distance, 0);
  }
  return pk.bytes();
}

void Model::override_friction(const std::optional<FrictionOverride>& friction) {
  friction_ = friction;
  const std::vector<unsigned char> packed = pack_pairs();
  device_->write(pair_buf_.get(), packed.size(), packed.data());
}

size_t Model::device_bytes() const {
  const size_t clumps = scene_.clumps.empty()
                            ? 0
                            : scene_.clumps.size() * (4 * real_size() + 8) +
                                  scene_.particles.size() * (4 * real_size() + 4);
  return pairs_.pairs.size() * config().pair_record() * real_size() +
         scene_.walls.size() * 16 * real_size() + clumps;
}

}  // namespace simsols
