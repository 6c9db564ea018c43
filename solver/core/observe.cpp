#include "solver/core/observe.h"

#include <cstring>

#include "solver/core/kernel_args.h"
#include "solver/core/pipeline.h"

namespace simsols {
namespace {

template <typename T>
std::vector<T> read_array(const Model& m, const Buffer& b, size_t count) {
  std::vector<T> v(count);
  m.device().read(b.get(), count * sizeof(T), v.data());
  return v;
}

}  // namespace

std::vector<double> read_reals(const Model& m, const Buffer& b, size_t count, size_t first) {
  std::vector<double> out(count);
  if (m.config().double_precision) {
    m.device().read(b.get(), count * sizeof(double), out.data(), first * sizeof(double));
  } else {
    std::vector<float> f(count);
    m.device().read(b.get(), count * sizeof(float), f.data(), first * sizeof(float));
    for (size_t i = 0; i < count; ++i) out[i] = f[i];
  }
  return out;
}

namespace {

// The device measures positions from the model's float frame (Model::
// origin); moments about the scene origin add origin x P, and the
// gravitational energy relative to it -M g.origin.
void refer_to_scene_origin(const Model& m, Observables& o) {
  const Vec3& c = m.origin();
  if (c[0] == 0 && c[1] == 0 && c[2] == 0) return;
  const Vec3 shift = cross(c, o.momentum);
  for (int a = 0; a < 3; ++a) o.angular_momentum[a] += shift[a];
  if (m.config().gravity)
    o.gravitational_energy -= m.total_mass() * dot(m.scene().effects.gravity, c);
}

}  // namespace

Observables observe(const Model& m, State& s) {
  constexpr int kObs = 12;  // NOBS in reduce.cl
  const Kernels& k = m.kernels();
  set_args(m, k.reduce_observables, arg("pos", s.pos), arg("pos_lo", s.pos_lo), arg("vel", s.vel),
           arg("omega", s.omega), arg("force", s.force), arg("torque", s.torque),
           arg("partial", s.obs_partial), arg("gravity", gravity_arg(m)), arg("dt", Real{m.dt()}),
           arg("n", s.n), arg("scratch", Local{m.local_size() * kObs * m.real_size()}));
  launch(m, k.reduce_observables, s.n);
  const size_t groups = m.global_size(s.n) / m.local_size();
  const std::vector<double> part = read_reals(m, s.obs_partial, groups * kObs);
  double sum[kObs] = {};
  for (size_t g = 0; g < groups; ++g)
    for (int c = 0; c < kObs; ++c) sum[c] += part[g * kObs + c];
  Observables o;
  o.kinetic_translational = sum[0];
  o.kinetic_rotational = sum[1];
  o.elastic_energy = sum[2];
  o.contacts = sum[3];
  o.momentum = {sum[4], sum[5], sum[6]};
  o.angular_momentum = {sum[7], sum[8], sum[9]};
  o.gravitational_energy = sum[10];
  o.particles = sum[11];
  refer_to_scene_origin(m, o);
  return o;
}

std::vector<WallReaction> wall_reactions(const Model& m, State& s) {
  std::vector<WallReaction> out(m.walls());
  if (out.empty()) return out;
  const size_t groups = reduce_wall_forces(m, s);
  const std::vector<double> part = read_reals(m, s.wall_partial, groups * m.walls() * 4);
  for (int w = 0; w < m.walls(); ++w) {
    double c = 0;
    for (size_t g = 0; g < groups; ++g) {
      const double* p = &part[(w * groups + g) * 4];
      for (int a = 0; a < 3; ++a) out[w].force[a] += p[a];
      c += p[3];
    }
    out[w].contacts = static_cast<int>(c + 0.5);
  }
  return out;
}

std::vector<Vec3> wall_points(const Model& m, State& s) {
  const int nw = m.walls();
  const std::vector<double> hi = read_reals(m, s.wall_point, size_t(nw) * 4);
  std::vector<float> lo;
  if (!m.config().double_precision && nw > 0)
    lo = read_array<float>(m, s.wall_point_lo, size_t(nw) * 4);
  std::vector<Vec3> out(nw);
  for (int w = 0; w < nw; ++w)
    for (int a = 0; a < 3; ++a)
      out[w][a] = m.origin()[a] + hi[w * 4 + a] + (lo.empty() ? 0.0 : double(lo[w * 4 + a]));
  return out;
}

ParticleSnapshot download(const Model& m, State& s) {
  const size_t n = s.n;
  const std::vector<double> pos = read_reals(m, s.pos, n * 4);
  const std::vector<double> vel = read_reals(m, s.vel, n * 4);
  const std::vector<double> om = read_reals(m, s.omega, n * 4);
  const std::vector<double> f = read_reals(m, s.force, n * 4);
  std::vector<float> lo;
  if (!m.config().double_precision) lo = read_array<float>(m, s.pos_lo, n * 4);
  // wall contacts are counted into force.w by wall_forces as well
  ParticleSnapshot p;
  p.position.resize(n);
  p.velocity.resize(n);
  p.angular_velocity.resize(n);
  p.force.resize(n);
  p.radius.resize(n);
  p.material.resize(n);
  p.contacts.resize(n);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      p.position[i][a] =
          m.origin()[a] + pos[4 * i + a] + (lo.empty() ? 0.0 : double(lo[4 * i + a]));
      p.velocity[i][a] = vel[4 * i + a];
      p.angular_velocity[i][a] = om[4 * i + a];
      p.force[i][a] = f[4 * i + a];
    }
    p.radius[i] = pos[4 * i + 3];
    p.material[i] = static_cast<int>(om[4 * i + 3]);
    p.contacts[i] = static_cast<int>(f[4 * i + 3]);
  }
  return p;
}

UpperLists read_upper_lists(const Model& m, State& s) {
  return {m.config().slice, read_array<int>(m, s.nbr_upper, s.n),
          read_array<std::uint32_t>(m, s.up_off, s.slices + 1),
          read_array<int>(m, s.nbr, s.up_slots)};
}

WallSlots read_wall_slots(const Model& m, State& s) {
  return {m.config().slice, read_array<int>(m, s.wall_near, s.n),
          read_array<std::uint32_t>(m, s.wall_off, s.slices + 1)};
}

std::vector<ClumpState> clump_states(const Model& m, State& s) {
  const int n = m.clumps();
  std::vector<ClumpState> out(n);
  if (n == 0) return out;
  const std::vector<double> x = read_reals(m, s.clump_pos, 4 * size_t(n));
  const std::vector<double> q = read_reals(m, s.clump_quat, 4 * size_t(n));
  const std::vector<double> v = read_reals(m, s.clump_vel, 4 * size_t(n));
  const std::vector<double> l = read_reals(m, s.clump_mom, 4 * size_t(n));
  std::vector<float> lo(4 * size_t(n), 0.0f);
  if (!m.config().double_precision)
    m.device().read(s.clump_pos_lo.get(), lo.size() * sizeof(float), lo.data());
  const Scene& sc = m.scene();
  for (int c = 0; c < n; ++c) {
    ClumpState& k = out[c];
    const size_t b = 4 * size_t(c);
    for (int a = 0; a < 3; ++a) {
      k.position[a] = x[b + a] + double(lo[b + a]) + m.origin()[a];
      k.velocity[a] = v[b + a];
      k.angular_momentum[a] = l[b + a];
    }
    k.orientation = {q[b + 3], q[b], q[b + 1], q[b + 2]};
    const Clump& clump = sc.clumps[c];
    const GrainBody g = scaled(m.grain_bodies()[clump.grain], clump.scale);
    const double rho = sc.materials[clump.material].density, mass = rho * g.mass.volume;
    const Quaternion conj = {k.orientation[0], -k.orientation[1], -k.orientation[2], -k.orientation[3]};
    const Vec3 lb = quat_rotate(conj, k.angular_momentum);
    Vec3 wb{};
    k.kinetic_energy = 0.5 * mass * dot(k.velocity, k.velocity);
    for (int a = 0; a < 3; ++a) {
      wb[a] = lb[a] / (rho * g.mass.principal[a]);
      k.kinetic_energy += 0.5 * lb[a] * wb[a];
    }
    k.angular_velocity = quat_rotate(k.orientation, wb);
  }
  return out;
}

std::vector<ContactForce> contact_list(const Model& m, State& s) {
  const int n = s.n;
  std::vector<ContactForce> out;
  if (n == 0) return out;
  const UpperLists l = read_upper_lists(m, s);
  const std::vector<int>& upper = l.upper;
  const std::vector<int>& nbr = l.nbr;
  // per slot, the force record then the torque record (store_shares, common.cl)
  const std::vector<double> pf = read_reals(m, s.share, size_t(s.up_slots) * 8);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < upper[i]; ++k) {
      const size_t slot = l.slot(i, k);
      if (pf[slot * 8 + 3] == 0) continue;  // listed, not touching
      out.push_back({i, nbr[slot], {-pf[slot * 8], -pf[slot * 8 + 1], -pf[slot * 8 + 2]}});
    }
  if (m.config().walls) {
    const int nw = m.walls();
    const WallSlots ws = read_wall_slots(m, s);
    const std::vector<double> wf = read_reals(m, s.wall_force, size_t(s.wall_slots) * 4);
    for (int w = 0; w < nw; ++w)
      for (int i = 0; i < n; ++i) {
        if (!ws.near(i, w)) continue;
        const double* f = &wf[ws.slot(i, w) * 4];
        if (f[3] == 0) continue;
        out.push_back({i, -1 - w, {-f[0], -f[1], -f[2]}});
      }
  }
  return out;
}

std::uint64_t state_hash(const Model& m, State& s) {
  std::uint64_t h = 1469598103934665603ull;
  std::vector<unsigned char> bytes;
  for (auto& [name, buf] : s.dynamic_buffers()) {
    bytes.resize(buf->bytes);
    m.device().read(buf->get(), buf->bytes, bytes.data());
    for (unsigned char c : bytes) {
      h ^= c;
      h *= 1099511628211ull;
    }
  }
  return h;
}

}  // namespace simsols
