// Model: a Scene compiled for one OpenCL device.
//
// Static after construction, like the Scene it comes from: the kernel
// program built for the scene's configuration, the kernels, the derived
// numerics (time step, skin, grid cell size, origin of the float frame) and
// the device copies of the constants (pair coefficient table, wall geometry).
// Everything that changes during a run is in State.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "solver/core/cl_device.h"
#include "solver/core/cl_program.h"
#include "solver/scene/clump.h"
#include "solver/scene/contact_model.h"
#include "solver/scene/scene.h"

namespace simsols {

struct Kernels {
  Kernel grid_clear, grid_count, scan_chunks, scan_totals, scan_apply, grid_scatter;
  Kernel count_neighbors, slice_widths, build_neighbors, build_mirrors;
  Kernel pair_forces, finish_particles, advance_walls, build_wall_near, wall_widths,
      carry_wall_slots, reset_wall_travel;
  Kernel reduce_observables, reduce_walls, servo_walls;
  Kernel move_clumps;
  Kernel membrane_forces;
  Kernel wrap_positions;
};

class Model {
 public:
  // Throws SceneError for scenes the device cannot run, DeviceError for
  // OpenCL failures (kernel build log included).
  Model(std::shared_ptr<Device> device, const Scene& scene);

  Device& device() const { return *device_; }
  const Scene& scene() const { return scene_; }
  const Program& program() const { return *program_; }
  const KernelConfig& config() const { return program_->config(); }
  const PairTable& pairs() const { return pairs_; }
  const Kernels& kernels() const { return kernels_; }

  int particles() const { return static_cast<int>(scene_.particles.size()); }
  int walls() const { return static_cast<int>(scene_.walls.size()); }
  double dt() const { return dt_; }
  double rayleigh_dt() const { return rayleigh_dt_; }
  double skin() const { return skin_; }
  double cell_size() const { return cell_size_; }
  const Vec3& origin() const { return origin_; }  // positions on the device are relative to it
  double total_mass() const { return total_mass_; }  // kg, of every particle
  size_t real_size() const { return config().double_precision ? 8 : 4; }
  size_t local_size() const { return local_size_; }
  size_t global_size(size_t n) const { return (n + local_size_ - 1) / local_size_ * local_size_; }

  // Clumps (scene.h, Clump; kernels/clumps.cl): per clump (M, I1, I2, I3)
  // and its member range; per particle its clump (-1 for a free sphere)
  // and its offset in the clump's body frame; a one-entry stand-in when
  // the scene has none. The grains as rigid bodies (clump.h), per grain.
  int clumps() const { return static_cast<int>(scene_.clumps.size()); }
  cl_mem clump_buffer() const { return clump_buf_.get(); }
  cl_mem clump_member_buffer() const { return clump_member_buf_.get(); }
  cl_mem body_buffer() const { return body_buf_.get(); }
  cl_mem body_offset_buffer() const { return body_offset_buf_.get(); }
  const std::vector<GrainBody>& grain_bodies() const { return grain_bodies_; }
  // kg: a free sphere's own; a member's share of its clump, by volume
  double particle_mass(int i) const { return particle_mass_[i]; }

  cl_mem pair_buffer() const { return pair_buf_.get(); }
  cl_mem wall_buffer() const { return wall_buf_.get(); }
  size_t device_bytes() const;  // of the constant buffers

  // A specimen's preparation (scene.h, Preparation) may settle it with
  // other friction than its materials': while `friction` is set, every
  // pair slides with mu_s = friction->sliding and rolls with
  // friction->rolling (each the materials' where unset), and collides with
  // friction->restitution (a periodic cell's compression; the kernels must
  // have damping compiled). The only change of the model after
  // construction; std::nullopt restores the scene's table.
  struct FrictionOverride {
    std::optional<double> sliding, rolling, restitution;
  };
  void override_friction(const std::optional<FrictionOverride>& friction);
  const std::optional<FrictionOverride>& friction_override() const { return friction_; }

 private:
  std::vector<unsigned char> pack_pairs() const;

  std::shared_ptr<Device> device_;
  Scene scene_;
  std::unique_ptr<Program> program_;
  Kernels kernels_;
  PairTable pairs_;
  double dt_ = 0, rayleigh_dt_ = 0, skin_ = 0, cell_size_ = 0;
  Vec3 origin_{};
  double total_mass_ = 0;
  size_t local_size_ = 64;
  ClMem pair_buf_, wall_buf_;
  ClMem clump_buf_, clump_member_buf_, body_buf_, body_offset_buf_;
  std::vector<GrainBody> grain_bodies_;
  std::vector<double> particle_mass_;
  std::optional<FrictionOverride> friction_;
  void make_clumps();
};

}  // namespace simsols
