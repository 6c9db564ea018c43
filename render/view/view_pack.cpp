#include "render/view/view_pack.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "solver/core/kernel_args.h"
#include "solver/core/real_packer.h"

namespace simsols {

// The packing kernels (render_pack.cl), embedded by render/view/CMakeLists.txt.
std::span<const KernelFile> render_kernel_files();

namespace {

constexpr const char* kNames[] = {"size",     "layer",    "speed", "displacement",
                                  "contacts", "rotation", "grain", "nonaffine"};
constexpr const char* kUnits[] = {"m", "", "m/s", "m", "", "rad/s", "", "m"};

// A point relative to the model origin, split for the device: hi in the
// device precision and, in float runs, lo = what the float could not hold
// (the compensated form of common.cl).
struct Split {
  Real4 hi, lo;
};
Split split(const Model& m, const Vec3& absolute) {
  Split s{{0, 0, 0, 0}, {0, 0, 0, 0}};
  double* hi[3] = {&s.hi.x, &s.hi.y, &s.hi.z};
  double* lo[3] = {&s.lo.x, &s.lo.y, &s.lo.z};
  for (int a = 0; a < 3; ++a) {
    const double rel = absolute[a] - m.origin()[a];
    if (m.config().double_precision) {
      *hi[a] = rel;
    } else {
      *hi[a] = static_cast<float>(rel);
      *lo[a] = float_remainder(rel);
    }
  }
  return s;
}

size_t mem_size(cl_mem mem) {
  size_t bytes = 0;
  check(clGetMemObjectInfo(mem, CL_MEM_SIZE, sizeof bytes, &bytes, nullptr),
        "clGetMemObjectInfo(CL_MEM_SIZE)");
  return bytes;
}

void require_buffer(cl_mem mem, size_t bytes, const char* what) {
  if (!mem) throw std::invalid_argument(std::string("ViewPacker: no ") + what + " buffer");
  const size_t have = mem_size(mem);
  if (have < bytes)
    throw std::invalid_argument(std::string("ViewPacker: the ") + what + " buffer holds " +
                                std::to_string(have) + " bytes, " + std::to_string(bytes) +
                                " needed");
}

Buffer make_buffer(Device& d, size_t bytes, const void* init = nullptr) {
  Buffer b;
  b.mem = d.alloc(bytes, init);
  b.bytes = bytes;
  return b;
}

std::vector<Vec3> initial_positions(const Scene& scene) {
  std::vector<Vec3> p;
  p.reserve(scene.particles.size());
  for (const Particle& q : scene.particles) p.push_back(q.position);
  return p;
}

}  // namespace

AffineFit affine_fit(const std::vector<Vec3>& reference, const std::vector<Vec3>& current) {
  if (reference.empty() || reference.size() != current.size())
    throw std::invalid_argument("affine_fit: " + std::to_string(reference.size()) +
                                " reference points and " + std::to_string(current.size()) +
                                " current ones (the same number, at least one)");
  const double n = static_cast<double>(reference.size());
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < reference.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      c[a] += reference[i][a] / n;
      mean[a] += (current[i][a] - reference[i][a]) / n;
    }
  // normal equations: (X^T X) A^T = X^T U, X the centred reference points,
  // U the displacements less their mean
  Eigen::Matrix3d xx = Eigen::Matrix3d::Zero(), xu = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < reference.size(); ++i) {
    Eigen::Vector3d x, u;
    for (int a = 0; a < 3; ++a) {
      x[a] = reference[i][a] - c[a];
      u[a] = current[i][a] - reference[i][a] - mean[a];
    }
    xx += x * x.transpose();
    xu += x * u.transpose();
  }
  const Eigen::Matrix3d at = xx.completeOrthogonalDecomposition().solve(xu);
  AffineFit f;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) f.a[r][k] = at(k, r);
    f.centre[r] = c[r];
    f.mean[r] = mean[r];
  }
  return f;
}

const char* to_string(ColorField f) { return kNames[static_cast<int>(f)]; }

const char* unit_of(ColorField f) { return kUnits[static_cast<int>(f)]; }

std::string color_field_names(char separator) {
  const std::string sep = separator == ',' ? ", " : std::string(1, separator);
  std::string s;
  for (ColorField f : kColorFields) s += (s.empty() ? "" : sep) + std::string(to_string(f));
  return s;
}

ColorField default_color_field(const Scene& scene) {
  return scene.clumps.empty() ? ColorField::Layer : ColorField::Grain;
}

std::optional<ColorField> parse_color_field(std::string_view s) {
  for (ColorField f : kColorFields) {
    const std::string_view name = to_string(f);
    if (name.size() == s.size() && std::equal(s.begin(), s.end(), name.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) == b;
        }))
      return f;
  }
  return std::nullopt;
}

ViewPacker::ViewPacker(Simulation& sim) : sim_(sim), n_(sim.state().n) {
  const Model& m = sim_.model();
  const Scene& scene = m.scene();
  Device& d = m.device();
  // The view origin: centre of the initial packing's bounding box.
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  double diameters = 0;
  for (const Particle& q : scene.particles) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], q.position[a]);
      hi[a] = std::max(hi[a], q.position[a]);
    }
    diameters += 2 * q.radius;
  }
  for (int a = 0; a < 3; ++a) origin_[a] = 0.5 * (lo[a] + hi[a]);
  band_ = diameters / n_;

  const size_t r4 = 4 * m.real_size();
  ref_ = make_buffer(d, n_ * r4);
  // float runs only: the compensation of the reference (a placeholder otherwise)
  ref_lo_ = make_buffer(d, m.config().double_precision ? 16 : n_ * 16);
  const std::vector<Vec3> initial = initial_positions(scene);
  write_reference(initial);
  follow_reference_bottom(initial);

  const size_t groups = m.global_size(n_) / m.local_size();
  bead_partial_ = make_buffer(d, groups * 2 * sizeof(float));
  contact_partial_ = make_buffer(d, groups * 3 * m.real_size());
  counter_ = make_buffer(d, sizeof(int));
}

void ViewPacker::build() {
  if (program_) return;
  const Model& m = sim_.model();
  // The solver's options (precision, walls, list layout); the packing code is
  // scalar, so LANES = 1 whatever the solver uses.
  KernelConfig config = m.config();
  config.lanes = 1;
  std::vector<KernelFile> files{kernel_file("layout.h"), kernel_file("common.cl")};
  for (const KernelFile& f : render_kernel_files()) files.push_back(f);
  auto program = std::make_unique<Program>(m.device(), config, files);
  pack_beads_ = program->kernel("pack_beads");
  pack_contacts_ = program->kernel("pack_contacts");
  program_ = std::move(program);
}

void ViewPacker::set_origin(const Vec3& origin) {
  for (double c : origin)
    if (!std::isfinite(c)) throw std::invalid_argument("ViewPacker::set_origin: not finite");
  origin_ = origin;
}

void ViewPacker::write_reference(const std::vector<Vec3>& p) {
  const Model& m = sim_.model();
  const bool dbl = m.config().double_precision;
  RealPacker hi(dbl), lo(false);
  for (const Vec3& x : p) {
    const Split s = split(m, x);
    hi.put4(s.hi.x, s.hi.y, s.hi.z, 0);
    lo.put_float4(s.lo.x, s.lo.y, s.lo.z, 0);
  }
  m.device().write(ref_.get(), hi.size(), hi.data());
  if (!dbl) m.device().write(ref_lo_.get(), lo.size(), lo.data());
  ref_host_ = p;
}

void ViewPacker::follow_reference_bottom(const std::vector<Vec3>& p) {
  if (user_bands_) return;
  z0_ = 1e300;
  for (const Vec3& x : p) z0_ = std::min(z0_, x[2]);
}

void ViewPacker::set_reference() {
  const Model& m = sim_.model();
  State& s = sim_.state();
  // A copy on the device: bit for bit the current (compensated) positions.
  cl_command_queue q = m.device().queue();
  check(clEnqueueCopyBuffer(q, s.pos.get(), ref_.get(), 0, 0, ref_.bytes, 0, nullptr, nullptr),
        "clEnqueueCopyBuffer(reference)");
  if (!m.config().double_precision)
    check(clEnqueueCopyBuffer(q, s.pos_lo.get(), ref_lo_.get(), 0, 0, ref_lo_.bytes, 0, nullptr,
                              nullptr),
          "clEnqueueCopyBuffer(reference lo)");
  ref_host_ = download(m, s).position;
  if (!user_bands_) follow_reference_bottom(ref_host_);
}

void ViewPacker::set_reference(const std::vector<Vec3>& absolute_positions) {
  if (absolute_positions.size() != static_cast<size_t>(n_))
    throw std::invalid_argument(
        "ViewPacker::set_reference: " + std::to_string(absolute_positions.size()) +
        " positions for " + std::to_string(n_) + " beads");
  write_reference(absolute_positions);
  follow_reference_bottom(absolute_positions);
}

void ViewPacker::set_layer_bands(double z0, double band) {
  if (!std::isfinite(z0) || !std::isfinite(band) || band <= 0)
    throw std::invalid_argument(
        "ViewPacker::set_layer_bands: need a finite z0 and band > 0 (got z0 = " +
        std::to_string(z0) + ", band = " + std::to_string(band) + ")");
  z0_ = z0;
  band_ = band;
  user_bands_ = true;
}

AffineFit ViewPacker::field_fit(ColorField field) {
  if (field != ColorField::NonAffine) return {};
  return affine_fit(ref_host_, download(sim_.model(), sim_.state()).position);
}

ViewPacker::Range ViewPacker::pack_beads(ColorField field, cl_mem beads, cl_mem values) {
  require_buffer(beads, size_t(n_) * 4 * sizeof(float), "beads");
  require_buffer(values, size_t(n_) * sizeof(float), "values");
  build();
  const Model& m = sim_.model();
  State& s = sim_.state();
  const Split o = split(m, origin_);
  const Split z0 = split(m, {origin_[0], origin_[1], z0_});
  const AffineFit fit = field_fit(field);
  const Split centre = split(m, fit.centre);
  const Real4 a0{fit.a[0][0], fit.a[0][1], fit.a[0][2], 0}, a1{fit.a[1][0], fit.a[1][1], fit.a[1][2], 0},
      a2{fit.a[2][0], fit.a[2][1], fit.a[2][2], 0}, mean{fit.mean[0], fit.mean[1], fit.mean[2], 0};
  set_args(m, pack_beads_, arg("pos", s.pos), arg("pos_lo", s.pos_lo), arg("vel", s.vel),
           arg("omega", s.omega), arg("force", s.force), arg("ref", ref_), arg("ref_lo", ref_lo_),
           arg("body", m.body_buffer()), arg("clumps", m.clumps()), arg("origin", o.hi),
           arg("origin_lo", o.lo), arg("field", static_cast<int>(field)),
           arg("z0", Real{z0.hi.z}), arg("z0_lo", Real{z0.lo.z}), arg("band", Real{band_}),
           arg("affine_a0", a0), arg("affine_a1", a1), arg("affine_a2", a2),
           arg("affine_centre", centre.hi), arg("affine_mean", mean), arg("beads", beads), arg("values", values), arg("partial", bead_partial_), arg("n", n_),
           arg("scratch", Local{m.local_size() * 2 * sizeof(float)}));
  launch(m, pack_beads_, n_);
  const size_t groups = m.global_size(n_) / m.local_size();
  std::vector<float> part(groups * 2);
  m.device().read(bead_partial_.get(), part.size() * sizeof(float), part.data());
  Range r{part[0], part[1]};
  for (size_t g = 1; g < groups; ++g) {
    r.min = std::min(r.min, part[2 * g]);
    r.max = std::max(r.max, part[2 * g + 1]);
  }
  return r;
}

ViewPacker::ContactStats ViewPacker::pack_contacts(cl_mem segments, size_t capacity, bool walls) {
  if (capacity == 0) throw std::invalid_argument("ViewPacker::pack_contacts: capacity must be > 0");
  if (capacity > static_cast<size_t>(INT_MAX) / 2)
    throw std::invalid_argument("ViewPacker::pack_contacts: capacity " + std::to_string(capacity) +
                                " is too large");
  require_buffer(segments, capacity * 8 * sizeof(float), "segments");
  build();
  const Model& m = sim_.model();
  State& s = sim_.state();
  const int nwalls = walls && m.config().walls ? m.walls() : 0;
  const Split o = split(m, origin_);
  m.device().fill_zero(counter_.get(), sizeof(int));
  set_args(m, pack_contacts_, arg("pos", s.pos), arg("pos_lo", s.pos_lo), arg("up_off", s.up_off),
           arg("nbr", s.nbr), arg("nbr_upper", s.nbr_upper), arg("pair_force", s.share),
           arg("walls", m.wall_buffer()), arg("wall_point", s.wall_point),
           arg("wall_point_lo", s.wall_point_lo), arg("wall_turn", s.wall_turn),
           arg("wall_near", s.wall_near),
           arg("wall_off", s.wall_off), arg("wall_force", s.wall_force), arg("origin", o.hi),
           arg("origin_lo", o.lo), arg("segments", segments), arg("counter", counter_),
           arg("capacity", static_cast<int>(capacity)), arg("partial", contact_partial_),
           arg("n", n_), arg("nwalls", nwalls),
           arg("scratch", Local{m.local_size() * 3 * m.real_size()}));
  launch(m, pack_contacts_, n_);
  const size_t groups = m.global_size(n_) / m.local_size();
  const std::vector<double> part = read_reals(m, contact_partial_, groups * 3);
  double total = 0, sum = 0, most = 0;
  for (size_t g = 0; g < groups; ++g) {
    total += part[3 * g];
    sum += part[3 * g + 1];
    most = std::max(most, part[3 * g + 2]);
  }
  ContactStats st;
  st.total = static_cast<size_t>(total + 0.5);
  st.count = std::min(st.total, capacity);
  st.mean_force = st.total ? sum / double(st.total) : 0.0;
  st.max_force = most;
  return st;
}

ViewPacker::HostBeads ViewPacker::pack_beads_host(ColorField field) {
  Device& d = sim_.model().device();
  const ClMem beads = d.alloc(size_t(n_) * 4 * sizeof(float));
  const ClMem values = d.alloc(size_t(n_) * sizeof(float));
  HostBeads out;
  out.range = pack_beads(field, beads.get(), values.get());
  out.xyzr.resize(size_t(n_) * 4);
  out.values.resize(n_);
  d.read(beads.get(), out.xyzr.size() * sizeof(float), out.xyzr.data());
  d.read(values.get(), out.values.size() * sizeof(float), out.values.data());
  return out;
}

ViewPacker::HostContacts ViewPacker::pack_contacts_host(size_t capacity, bool walls) {
  if (capacity == 0)
    throw std::invalid_argument("ViewPacker::pack_contacts_host: capacity must be > 0");
  Device& d = sim_.model().device();
  const ClMem segments = d.alloc(capacity * 8 * sizeof(float));
  HostContacts out;
  out.stats = pack_contacts(segments.get(), capacity, walls);
  out.segments.resize(out.stats.count * 8);
  d.read(segments.get(), out.segments.size() * sizeof(float), out.segments.data());
  return out;
}

}  // namespace simsols
