// Kernel program: the embedded .cl sources built for one configuration.
//
// A KernelConfig is derived from the Scene (make_kernel_config): precision
// and the optional physics the scene uses become -D options, so a scene pays
// only for what it calls for (MuJoCo's "disable flags", decided at build
// time instead of at run time). A failed build throws DeviceError carrying
// the full build log; nothing fails silently.
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "solver/core/cl_device.h"
#include "solver/kernels/kernel_source.h"
#include "solver/kernels/layout.h"
#include "solver/scene/scene.h"

namespace simsols {

// One flag per effect slot (scene.h, Effects): a slot whose choice is none,
// or whose coefficients are zero for every material pair, is not compiled.
// Each compiled sub-model declares the per-contact history it needs
// (LAMMPS GRANULAR style); the list and wall slots carry exactly that.
struct KernelConfig {
  bool double_precision = true;
  bool gravity = true;
  bool damping = true;        // slot damping = viscous
  bool friction = true;       // slot tangential = mindlin or mindlin_deresiewicz
  bool micro_slip = false;    // tangential = mindlin_deresiewicz (else mindlin)
  bool rolling = true;        // slot rolling = constant_torque or spring_dashpot
  bool rolling_spring = false;  // rolling = spring_dashpot (else constant torque)
  bool capillary = false;     // slot cohesion = capillary
  bool fluid = false;         // slot fluid = drag
  bool walls = true;
  bool servo = false;  // some wall is servo-controlled
  bool tilt = false;   // some wall may turn (Wall::tilts; walls.cl, HAS_TILT)
  bool clumps = false;  // the scene has clumps (clumps.cl)
  bool membrane = false;  // the scene has a membrane of bonded beads (membrane.cl)
  bool periodic = false;  // a periodic cell (periodic.cl)
  int lanes = 1;                   // particles per work item in the contact kernels
  int slice = 32;                  // particles per slice of the neighbour lists (neighbors.cl)
  // finish_particles asks for the shares two work items on will collect
  // (CPUs, lanes > 1; forces.cl, prefetch_shares)
  bool prefetch_shares = false;
  std::string extra_options;       // appended verbatim (diagnostics, tests)

  std::string build_options() const;

  // Per-contact history: one plane (a record of 4 reals per contact) for
  // each compiled sub-model that keeps state, as history_plane_table()
  // declares; 0 when nothing needs history.
  bool contact_record() const { return friction || damping; }
  // The walls' step at the end of finish_particles (CPUs, lanes > 1),
  // instead of a servo_walls launch (integrate.cl).
  bool servo_in_finish() const { return servo && lanes > 1; }
  // rolling = constant_torque shares its cap among a particle's contacts of
  // the previous step, whose counts are kept (State::touching) only then
  // (HAS_SHARED_ROLLING_CAP in the kernels).
  bool shared_rolling_cap() const { return rolling && !rolling_spring; }
  int history_planes() const;
  size_t real_size() const { return double_precision ? 8 : 4; }
  size_t history_bytes_per_contact() const { return history_planes() * 4 * real_size(); }
  // reals per pair coefficient record (layout.h, PairSlot)
  int pair_record() const { return capillary ? PAIR_RECORD_CAPILLARY : PAIR_RECORD_BASE; }
  bool operator==(const KernelConfig&) const = default;
};

KernelConfig make_kernel_config(const Scene& scene, const Device& device);

// The contact sub-models that keep per-contact history, each declaring its
// plane (LAMMPS GRANULAR's history slots). The compiled ones are numbered
// in this order and reach the kernels as -D<define>=<plane>; what each
// plane's 4 reals hold is written beside the laws (contact_law.cl,
// "Per-contact history"), which alone read and write them. The lists and
// the wall slots carry every plane without knowing what it holds.
struct HistoryPlane {
  const char* define;  // the kernels' name for its plane: "HIST_CONTACT"
  const char* slots;   // the effect slots that keep it, for --explain
  bool (*compiled)(const KernelConfig& c);
};
std::span<const HistoryPlane> history_plane_table();

// A kernel and the names of its parameters as the compiler reports them
// (programs are built with -cl-kernel-arg-info). set_args (kernel_args.h)
// binds every argument by name against them, so a call that names its
// arguments in another order than the kernel's signature, or leaves one
// out, stops with the kernel and the argument named instead of binding the
// wrong buffer. A driver that keeps no argument names leaves `params`
// empty: then only the count is checked.
struct Kernel {
  ClKernel handle;
  std::string name;
  std::vector<std::string> params;
  cl_uint count = 0;  // number of parameters
  // The (global, local) sizes it has been launched at, local 0 for the
  // driver's choice (enqueue_kernel); a cache, hence mutable.
  mutable std::vector<std::array<size_t, 2>> launched;
  cl_kernel get() const { return handle.get(); }
};

// Enqueues a 1-D range of `global` work items in work-groups of `local`
// (0: the driver's choice). Where the device compiles into a cache shared
// between processes (PoCL), the kernel's first launch at each size is when
// it compiles: that launch runs under the compile lock and is waited for
// (kernel_cache_lock.h). Later launches only enqueue.
void enqueue_kernel(Device& device, const Kernel& k, size_t global, size_t local);

class Program {
 public:
  // Builds the solver program (kernel_files()); throws DeviceError with the
  // build log on failure.
  Program(Device& device, const KernelConfig& config);
  // Builds the given embedded files, in order, with the same options (e.g.
  // common.cl + render_pack.cl for the renderer's packing kernels).
  Program(Device& device, const KernelConfig& config, std::span<const KernelFile> files);

  Kernel kernel(const char* name) const;  // throws DeviceError if absent
  const KernelConfig& config() const { return config_; }
  double build_seconds() const { return build_seconds_; }

 private:
  ClProgram program_;
  KernelConfig config_;
  double build_seconds_ = 0;
};

// The full program text for a configuration (prelude of #defines is passed
// as build options, not text). Exposed for tools and tests.
std::string program_source();
std::string program_source(std::span<const KernelFile> files);

// The embedded solver source named `name` (e.g. "common.cl"); throws
// DeviceError if there is none.
const KernelFile& kernel_file(std::string_view name);

}  // namespace simsols
