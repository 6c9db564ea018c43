#include "solver/core/cl_program.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

#include "solver/core/kernel_cache_lock.h"
#include "solver/kernels/kernel_source.h"

namespace simsols {

std::string KernelConfig::build_options() const {
  std::string o = "-cl-std=CL1.2 -cl-kernel-arg-info";
  if (double_precision) o += " -DSIMSOLS_DOUBLE";
  if (gravity) o += " -DHAS_GRAVITY";
  if (damping) o += " -DHAS_DAMPING";
  if (friction) o += " -DHAS_FRICTION";
  if (friction && micro_slip) o += " -DHAS_MD_TANGENTIAL";
  if (rolling) o += " -DHAS_ROLLING";
  if (rolling && rolling_spring) o += " -DHAS_ROLLING_SPRING";
  if (capillary) o += " -DHAS_CAPILLARY";
  if (fluid) o += " -DHAS_FLUID";
  o += " -DHIST_PLANES=" + std::to_string(history_planes());
  int plane = 0;  // the compiled sub-models' planes, numbered in the table's order
  for (const HistoryPlane& h : history_plane_table())
    if (h.compiled(*this)) o += std::string(" -D") + h.define + "=" + std::to_string(plane++);
  o += " -DPAIR_RECORD=" + std::to_string(pair_record());
  if (walls) o += " -DHAS_WALLS";
  if (servo) o += " -DHAS_SERVO";
  if (tilt) o += " -DHAS_TILT";
  if (servo_in_finish()) o += " -DSERVO_IN_FINISH";
  if (prefetch_shares) o += " -DPREFETCH_SHARES";
  if (clumps) o += " -DHAS_CLUMPS";
  if (membrane) o += " -DHAS_MEMBRANE";
  if (periodic) o += " -DHAS_PERIODIC";
  o += " -DSLICE=" + std::to_string(slice);
  o += " -DLANES=" + std::to_string(lanes);
  if (!extra_options.empty()) o += " " + extra_options;
  return o;
}

namespace {

// In plane order; contact_law.cl says what each holds.
constexpr HistoryPlane kHistoryPlanes[] = {
    {"HIST_CONTACT", "tangential = mindlin (its spring), damping = viscous (the dashpot's record)",
     [](const KernelConfig& c) { return c.contact_record(); }},
    {"HIST_ROLL", "rolling = spring_dashpot (the elastic rolling torque)",
     [](const KernelConfig& c) { return c.rolling && c.rolling_spring; }},
    {"HIST_TURN", "tangential = mindlin_deresiewicz (the force at the last turning point, the branch)",
     [](const KernelConfig& c) { return c.friction && c.micro_slip; }},
};

}  // namespace

std::span<const HistoryPlane> history_plane_table() { return kHistoryPlanes; }

int KernelConfig::history_planes() const {
  int n = 0;
  for (const HistoryPlane& h : kHistoryPlanes) n += h.compiled(*this) ? 1 : 0;
  return n;
}

namespace {

// What a periodic cell cannot hold (periodic.cl): a SceneError naming the field.
void check_periodic(const Scene& scene, const KernelConfig& c) {
  const std::string file = scene.source_path.empty() ? scene.name : scene.source_path;
  const auto refuse = [&](const char* field, const char* why) {
    throw SceneError("out_of_range", file, 0, field, why);
  };
  if (!c.double_precision)
    refuse("numerics.precision", "a periodic cell runs in double precision (\"double\")");
  if (c.walls) refuse("walls", "a periodic cell has no walls");
  if (c.clumps) refuse("clumps", "clumps in a periodic cell are not supported");
  if (c.membrane) refuse("membrane", "a periodic cell has no membrane");
  if (c.gravity) refuse("effects.gravity", "a periodic cell has no gravity (set it to [0, 0, 0])");
}

}  // namespace

KernelConfig make_kernel_config(const Scene& scene, const Device& device) {
  KernelConfig c;
  c.double_precision = scene.numerics.precision == Precision::Double;
  if (c.double_precision && !device.has_double())
    throw DeviceError("numerics.precision = \"double\" but the OpenCL device " + device.name() +
                      " has no cl_khr_fp64; use precision = \"float\"");
  c.gravity = scene.has_gravity();
  bool any_friction = false, any_rolling = false, any_damping = false;
  for (const Material& m : scene.materials) {
    any_friction = any_friction || m.sliding_friction > 0;
    any_rolling = any_rolling || m.rolling_friction > 0;
    any_damping = any_damping || m.restitution < 1;
  }
  for (const PairOverride& p : scene.pair_overrides) {
    any_friction = any_friction || p.sliding_friction.value_or(0) > 0;
    any_rolling = any_rolling || p.rolling_friction.value_or(0) > 0;
    any_damping = any_damping || p.restitution.value_or(1) < 1;
  }
  // a specimen may settle with friction its materials lack (Preparation)
  if (const Specimen* s = scene.specimen()) {
    any_friction = any_friction || s->preparation.friction.value_or(0) > 0;
    any_rolling = any_rolling || s->preparation.rolling_friction.value_or(0) > 0;
  }
  if (scene.periodic) {
    any_friction = any_friction || scene.periodic->preparation_friction > 0;
    any_damping = any_damping || scene.periodic->preparation_restitution < 1;
  }
  const Effects& e = scene.effects;
  c.damping = e.damping == DampingModel::Viscous && any_damping;
  c.friction = e.tangential != TangentialModel::None && any_friction;
  c.micro_slip = c.friction && e.tangential == TangentialModel::MindlinDeresiewicz;
  c.rolling = e.rolling != RollingModel::None && any_rolling;
  c.rolling_spring = c.rolling && e.rolling == RollingModel::SpringDashpot;
  c.capillary = e.cohesion == CohesionModel::Capillary;
  c.fluid = e.fluid == FluidModel::Drag;
  // a scene read but not placed will have its apparatus' walls, a servo
  // among them, and a specimen of clumps if it pours a grain (scene.h);
  // a periodic cell has none of them
  const bool pending = scene.apparatus_pending && !scene.periodic;  // a periodic cell adds no walls
  c.walls = !scene.walls.empty() || pending;
  c.servo = pending;
  for (const Wall& w : scene.walls) {
    c.servo = c.servo || w.servo.enabled;
    c.tilt = c.tilt || w.tilts;
  }
  c.clumps = !scene.clumps.empty() || (pending && scene.specimen() && scene.specimen()->grain >= 0);
  c.membrane = scene.membrane.count() > 0;
  c.periodic = scene.periodic.has_value();
  if (c.periodic) check_periodic(scene, c);
  // CPUs: SIMD lanes, 8 floats or 4 doubles per work item (256-bit
  // registers; measured fastest with PoCL 3.1 on AVX-512, docs/performance.md).
  // GPUs already run one particle per SIMD lane.
  c.lanes = device.is_gpu() ? 1 : (c.double_precision ? 4 : 8);
  if (device.options().lanes != 0) c.lanes = device.options().lanes;
  if (!allowed_lanes(c.lanes))
    throw DeviceError("EngineOptions::lanes (SIMSOLS_LANES) must be 1, 2, 4, 8 or 16, not " +
                      std::to_string(c.lanes));
  // List slices (neighbors.cl): a work item's lanes are one slice, so they
  // read consecutive slots; one particle per work item (GPUs) slices by 32,
  // a warp, so neighbouring threads do. SLICE must be a multiple of LANES.
  c.slice = c.lanes > 1 ? c.lanes : 32;
  // __builtin_prefetch is Clang's (PoCL); GPUs hide latency with threads
  c.prefetch_shares = c.lanes > 1 && !device.is_gpu() && device.options().prefetch;
  c.extra_options = device.options().cl_options;
  return c;
}

std::string program_source() { return program_source(kernel_files()); }

std::string program_source(std::span<const KernelFile> files) {
  std::string text;
  for (const KernelFile& f : files) {
    text += "#line 1 \"";
    text += f.name;
    text += "\"\n";
    text += f.text;
    text += "\n";
  }
  return text;
}

const KernelFile& kernel_file(std::string_view name) {
  for (const KernelFile& f : kernel_files())
    if (name == f.name) return f;
  throw DeviceError("no embedded kernel source named '" + std::string(name) + "'");
}

Program::Program(Device& device, const KernelConfig& config)
    : Program(device, config, kernel_files()) {}

Program::Program(Device& device, const KernelConfig& config, std::span<const KernelFile> files)
    : config_(config) {
  const std::string text = program_source(files);
  const char* src = text.c_str();
  const size_t len = text.size();
  cl_int err = CL_SUCCESS;
  program_ = ClProgram(clCreateProgramWithSource(device.context(), 1, &src, &len, &err));
  check(err, "clCreateProgramWithSource");
  const std::string options = config.build_options();
  cl_device_id id = device.id();
  const auto t0 = std::chrono::steady_clock::now();
  {
    const KernelCacheLock lock(device.compile_lock_path());
    err = clBuildProgram(program_.get(), 1, &id, options.c_str(), nullptr, nullptr);
  }
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (err != CL_SUCCESS) {
    size_t n = 0;
    clGetProgramBuildInfo(program_.get(), id, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
    std::string log(n, '\0');
    clGetProgramBuildInfo(program_.get(), id, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
    throw DeviceError("OpenCL kernel build failed (error " + std::to_string(err) +
                      ", options '" + options + "') on " + device.name() + ":\n" + log);
  }
}

Kernel Program::kernel(const char* name) const {
  cl_int err = CL_SUCCESS;
  cl_kernel k = clCreateKernel(program_.get(), name, &err);
  if (err != CL_SUCCESS)
    throw DeviceError(std::string("kernel '") + name + "' missing from the program (error " +
                      std::to_string(err) + ")");
  Kernel out{ClKernel(k), name, {}, 0, {}};
  check(clGetKernelInfo(k, CL_KERNEL_NUM_ARGS, sizeof out.count, &out.count, nullptr),
        "clGetKernelInfo(CL_KERNEL_NUM_ARGS)");
  for (cl_uint i = 0; i < out.count; ++i) {
    size_t n = 0;
    if (clGetKernelArgInfo(k, i, CL_KERNEL_ARG_NAME, 0, nullptr, &n) != CL_SUCCESS) {
      out.params.clear();  // no argument names kept: only the count is checked
      break;
    }
    std::string param(n, '\0');
    check(clGetKernelArgInfo(k, i, CL_KERNEL_ARG_NAME, n, param.data(), nullptr),
          "clGetKernelArgInfo(CL_KERNEL_ARG_NAME)");
    param.resize(std::strlen(param.c_str()));
    out.params.push_back(std::move(param));
  }
  return out;
}

void enqueue_kernel(Device& device, const Kernel& k, size_t global, size_t local) {
  const std::array<size_t, 2> size{global, local};
  const bool first = !device.compile_lock_path().empty() &&
                     std::find(k.launched.begin(), k.launched.end(), size) == k.launched.end();
  std::optional<KernelCacheLock> lock;
  if (first) lock.emplace(device.compile_lock_path());
  check(clEnqueueNDRangeKernel(device.queue(), k.get(), 1, nullptr, &global,
                               local != 0 ? &local : nullptr, 0, nullptr, nullptr),
        "clEnqueueNDRangeKernel");
  if (!first) return;
  device.finish();  // compiled and run: the cache is written before the lock goes
  k.launched.push_back(size);
}

}  // namespace simsols
