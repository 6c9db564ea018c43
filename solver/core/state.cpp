#include "solver/core/state.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "solver/core/pipeline.h"
#include "solver/core/real_packer.h"
#include "solver/kernels/layout.h"

namespace simsols {

double tilt_inverse_inertia(const Wall& w, const WallServo& c) {
  if (!w.tilts || !c.enabled || !(c.mass > 0) || !(w.half_u > 0)) return 0;
  return 3 / (c.mass * w.half_u * w.half_u);  // J = M (2 half_u)^2 / 12
}

std::array<double, 8> servo_record(const WallServo& c) {
  return {c.target_force, c.gain, c.max_speed, c.enabled ? 1.0 : 0.0,
          c.integral_time > 0 ? 1 / c.integral_time : 0, c.mass > 0 ? 1 / c.mass : 0,
          c.leader >= 0 ? c.leader + 1.0 : 0.0, c.stop};
}

namespace {

// List slots reserved per part at the start: numerics.neighbor_capacity
// (slots per particle, both parts) when set, else none; the first rebuild
// allocates what the lists need (pipeline.cpp).
int initial_slots(const Scene& scene, int n) {
  return scene.numerics.neighbor_capacity > 0 ? n * scene.numerics.neighbor_capacity / 2 : 0;
}

std::uint32_t next_pow2(std::uint64_t v) {
  std::uint32_t p = 1;
  while (p < v) p <<= 1;
  return p;
}

}  // namespace

Buffer State::make(Device& d, size_t bytes, const void* init) {
  Buffer b;
  b.mem = d.alloc(bytes, init);
  b.bytes = bytes;
  return b;
}

State::State(const Model& model) {
  n = model.particles();
  slices = (n + model.config().slice - 1) / model.config().slice;
  table = next_pow2(n);  // ~1-2 buckets per particle (one cell holds about one)
  chunk_len = (table + chunks - 1) / chunks;
  const float v2_start = make_particles(model);
  make_lists(model);
  make_grid(model.device());
  make_walls(model);
  make_servo(model);
  make_flags(model, v2_start);
  make_step_scratch(model);
  make_clumps(model);
  make_cell(model);
  make_membrane(model);
}

void State::make_cell(const Model& model) {
  cell = make(model.device(), CELL_REALS * model.real_size());
  model.device().fill_zero(cell.get(), cell.bytes);
  const std::optional<PeriodicBox>& box = model.scene().periodic;
  if (!box) return;
  cell_now.h = box->edges;
  cell_now.since_build = identity3();
  cell_now.corner = sub(box->corner, model.origin());
  write_cell(model, *this);
}

void State::make_membrane(const Model& model) {
  const Membrane& m = model.scene().membrane;
  membrane_beads = m.count();
  RealPacker r(model.config().double_precision);
  // held, no pressure until the apparatus sets them
  r.put4(0, 1, m.stiffness, m.stiffness);
  r.put4(0, 0, 0, 0);
  r.put4(m.first, m.rows, m.cols, m.platen_wall);
  r.put4(0, 0, 0, 0);
  membrane = make(model.device(), r.bytes().size(), r.data());
  membrane_force = make(model.device(), std::max(1, membrane_beads) * 4 * model.real_size());
}

void State::make_clumps(const Model& model) {
  Device& d = model.device();
  const Scene& s = model.scene();
  const bool dbl = model.config().double_precision;
  RealPacker x(dbl), lo(false), q(dbl), v(dbl), l(dbl);
  const Vec3& o = model.origin();
  for (const Clump& c : s.clumps) {
    const GrainBody b = scaled(model.grain_bodies()[c.grain], c.scale);
    double rel[3];
    for (int a = 0; a < 3; ++a) rel[a] = c.position[a] - o[a];
    x.put4(rel[0], rel[1], rel[2], 0);
    lo.put_float4(float_remainder(rel[0]), float_remainder(rel[1]), float_remainder(rel[2]), 0);
    const Quaternion r = body_orientation(c, b);
    q.put4(r[1], r[2], r[3], r[0]);
    v.put4(c.velocity[0], c.velocity[1], c.velocity[2], 0);
    // L = R I R^T w, I the principal moments times the density
    const double rho = s.materials[c.material].density;
    const Vec3 wb = quat_rotate({r[0], -r[1], -r[2], -r[3]}, c.angular_velocity);
    const Vec3 lb = {rho * b.mass.principal[0] * wb[0], rho * b.mass.principal[1] * wb[1],
                     rho * b.mass.principal[2] * wb[2]};
    const Vec3 ls = quat_rotate(r, lb);
    l.put4(ls[0], ls[1], ls[2], 0);
  }
  if (s.clumps.empty()) {  // one-record stand-ins
    for (RealPacker* p : {&x, &q, &v, &l}) p->put4(0, 0, 0, 0);
    lo.put_float4(0, 0, 0, 0);
  }
  clumps = static_cast<int>(s.clumps.size());
  clump_pos = make(d, x.bytes().size(), x.data());
  clump_pos_lo = make(d, lo.bytes().size(), lo.data());
  clump_quat = make(d, q.bytes().size(), q.data());
  clump_vel = make(d, v.bytes().size(), v.data());
  clump_mom = make(d, l.bytes().size(), l.data());
}

float State::make_particles(const Model& model) {
  Device& d = model.device();
  const Scene& s = model.scene();
  const bool dbl = model.config().double_precision;
  const size_t r4 = 4 * model.real_size();
  RealPacker p(dbl), lo(false), v(dbl), w(dbl);
  const Vec3& o = model.origin();
  float v2_start = 0;  // the largest |v|^2 at the start: the first list check's interval
  for (const Particle& q : s.particles) {
    v2_start = std::max(v2_start, static_cast<float>(q.velocity[0] * q.velocity[0] +
                                                     q.velocity[1] * q.velocity[1] +
                                                     q.velocity[2] * q.velocity[2]));
    const double mass = model.particle_mass(static_cast<int>(&q - s.particles.data()));
    double rel[3];
    for (int a = 0; a < 3; ++a) rel[a] = q.position[a] - o[a];
    p.put4(rel[0], rel[1], rel[2], q.radius);
    if (!dbl) {  // compensation: what the float position could not hold
      lo.put_float4(float_remainder(rel[0]), float_remainder(rel[1]), float_remainder(rel[2]), 0);
    }
    v.put4(q.velocity[0], q.velocity[1], q.velocity[2], mass);
    w.put4(q.angular_velocity[0], q.angular_velocity[1], q.angular_velocity[2], q.material);
  }
  pos = make(d, n * r4, p.data());
  pos_lo = make(d, dbl ? 16 : n * 16, dbl ? nullptr : lo.data());
  vel = make(d, n * r4, v.data());
  omega = make(d, n * r4, w.data());
  force = make(d, n * r4);
  torque = make(d, n * r4);
  pos_build = make(d, n * 16);  // float4 in every precision (integrate.cl)
  return v2_start;
}

void State::make_lists(const Model& model) {
  Device& d = model.device();
  nbr_count = make(d, n * sizeof(int));
  nbr_upper = make(d, n * sizeof(int));
  up_off = make(d, (slices + 1) * sizeof(std::uint32_t));
  lo_off = make(d, (slices + 1) * sizeof(std::uint32_t));
  old_up_off = make(d, (slices + 1) * sizeof(std::uint32_t));
  const int slots = initial_slots(model.scene(), n);
  resize_lists(model, slots, slots);
}

void State::make_grid(Device& d) {
  bucket = make(d, n * sizeof(std::uint32_t));
  slot = make(d, n * sizeof(std::uint32_t));
  cell_count = make(d, table * sizeof(std::uint32_t));
  cell_start = make(d, table * sizeof(std::uint32_t));
  sorted = make(d, n * sizeof(int));
  chunk_sum = make(d, chunks * sizeof(std::uint32_t));
}

void State::make_walls(const Model& model) {
  Device& d = model.device();
  const bool dbl = model.config().double_precision;
  const size_t r4 = 4 * model.real_size();
  const Vec3& o = model.origin();
  const int nw = model.walls();
  RealPacker wp(dbl), wlo(false), wv(dbl);
  for (const Wall& wall : model.scene().walls) {
    double rel[3];
    for (int a = 0; a < 3; ++a) rel[a] = wall.point[a] - o[a];
    wp.put4(rel[0], rel[1], rel[2], 0);
    wlo.put_float4(float_remainder(rel[0]), float_remainder(rel[1]), float_remainder(rel[2]), 0);
    wv.put4(wall.velocity[0], wall.velocity[1], wall.velocity[2], 0);
  }
  wall_point = make(d, nw * r4, wp.data());
  wall_point_lo = make(d, nw * 16, dbl ? nullptr : wlo.data());
  wall_vel = make(d, nw * r4, wv.data());
  wall_touch = make(d, n * sizeof(int));
  // no wall near any particle and no slot until the first list build (the
  // first step's: FLAG_REBUILD, make_flags)
  wall_near = make(d, nw ? n * sizeof(int) : 16);
  wall_off = make(d, (slices + 1) * sizeof(std::uint32_t));
  old_wall_off = make(d, (slices + 1) * sizeof(std::uint32_t));
  resize_walls(model, 0);
}

void State::make_servo(const Model& model) {
  Device& d = model.device();
  const size_t r4 = 4 * model.real_size();
  const int nw = model.walls();
  wall_reaction = make(d, std::max(1, nw) * r4);
  wall_mean = make(d, std::max(1, nw) * r4);
  RealPacker sv(model.config().double_precision);
  for (const Wall& wall : model.scene().walls) {
    const std::array<double, 8> c = servo_record(wall.servo);
    sv.put4(c[0], c[1], c[2], c[3]);
    sv.put4(c[4], c[5], c[6], c[7]);
  }
  servo = make(d, std::max(1, nw) * 2 * r4, nw ? sv.data() : nullptr);
  tilting = model.config().tilt;
  RealPacker turn(model.config().double_precision);
  for (const Wall& wall : model.scene().walls) turn.put4(0, 0, tilt_inverse_inertia(wall, wall.servo), 0);
  wall_turn = make(d, std::max(1, nw) * r4, nw && tilting ? turn.data() : nullptr);
}

void State::make_flags(const Model& model, float v2_start) {
  // the first step builds the lists, and sets the next check from the
  // fastest particle's start speed (FLAG_MAX_SPEED2, float bits), so a scene that
  // starts fast is checked as often as one that became fast; no runaway mark
  int v2_bits = 0;
  std::memcpy(&v2_bits, &v2_start, sizeof v2_bits);
  int init_flags[FLAG_SLOTS] = {};
  init_flags[FLAG_REBUILD] = 1;
  init_flags[FLAG_MAX_SPEED2] = v2_bits;
  init_flags[FLAG_RUNAWAY_FIRST] = kNoRunaway;
  flags = make(model.device(), sizeof init_flags, init_flags);
}

void State::make_step_scratch(const Model& model) {
  Device& d = model.device();
  const size_t r4 = 4 * model.real_size();
  const int nw = model.walls();
  touching = make(d, model.config().shared_rolling_cap() ? n * sizeof(int) : 16);
  const size_t groups = model.global_size(n) / model.local_size();
  obs_partial = make(d, groups * 12 * model.real_size());
  const size_t wall_chunks = std::max<size_t>(1, (n + kWallChunk - 1) / kWallChunk);
  // with tilting walls, the moments follow the forces (walls.cl, wall_chunk_sums)
  wall_partial = make(d, std::max(1, nw) * wall_chunks * r4 * (model.config().tilt ? 2 : 1));
  const int zero = 0;
  groups_done = make(d, sizeof zero, &zero);
}

std::vector<std::pair<std::string, const Buffer*>> State::all_buffers() const {
  return {{"pos", &pos},
          {"pos_lo", &pos_lo},
          {"vel", &vel},
          {"omega", &omega},
          {"force", &force},
          {"torque", &torque},
          {"pos_build", &pos_build},
          {"nbr_count", &nbr_count},
          {"nbr_upper", &nbr_upper},
          {"up_off", &up_off},
          {"lo_off", &lo_off},
          {"nbr", &nbr},
          {"spring", &spring},
          {"share", &share},
          {"mirror", &mirror},
          {"old_up_off", &old_up_off},
          {"bucket", &bucket},
          {"slot", &slot},
          {"cell_count", &cell_count},
          {"cell_start", &cell_start},
          {"sorted", &sorted},
          {"chunk_sum", &chunk_sum},
          {"wall_point", &wall_point},
          {"wall_point_lo", &wall_point_lo},
          {"wall_vel", &wall_vel},
          {"wall_touch", &wall_touch},
          {"wall_near", &wall_near},
          {"wall_off", &wall_off},
          {"wall_spring", &wall_spring},
          {"wall_force", &wall_force},
          {"old_wall_off", &old_wall_off},
          {"wall_reaction", &wall_reaction},
          {"wall_mean", &wall_mean},
          {"servo", &servo},
          {"wall_turn", &wall_turn},
          {"flags", &flags},
          {"obs_partial", &obs_partial},
          {"wall_partial", &wall_partial},
          {"groups_done", &groups_done},
          {"touching", &touching},
          {"clump_pos", &clump_pos},
          {"clump_pos_lo", &clump_pos_lo},
          {"clump_quat", &clump_quat},
          {"clump_vel", &clump_vel},
          {"clump_mom", &clump_mom},
          {"cell", &cell},
          {"membrane", &membrane},
          {"membrane_force", &membrane_force}};
}

size_t State::device_bytes() const {
  size_t total = 0;
  for (const auto& [name, b] : all_buffers()) total += b->bytes;
  return total;
}

std::vector<std::pair<std::string, Buffer*>> State::dynamic_buffers() {
  // Grid buffers are rebuilt from positions before use and are not state.
  std::vector<std::pair<std::string, Buffer*>> all = {{"pos", &pos},           {"pos_lo", &pos_lo},         {"vel", &vel},
          {"omega", &omega},       {"force", &force},           {"torque", &torque},
          {"pos_build", &pos_build}, {"nbr_count", &nbr_count}, {"nbr_upper", &nbr_upper},
          {"up_off", &up_off},     {"lo_off", &lo_off},       {"nbr", &nbr},
          {"spring", &spring},     {"mirror", &mirror},
          {"wall_point", &wall_point}, {"wall_point_lo", &wall_point_lo},
          {"wall_vel", &wall_vel}, {"wall_near", &wall_near}, {"wall_off", &wall_off},
          {"wall_spring", &wall_spring}, {"wall_force", &wall_force},
          {"wall_touch", &wall_touch}, {"wall_reaction", &wall_reaction}, {"wall_mean", &wall_mean}, {"servo", &servo},
          {"flags", &flags}};
  if (cell_now.h[0] != 0) all.emplace_back("cell", &cell);  // periodic scenes only
  if (tilting) all.emplace_back("wall_turn", &wall_turn);  // scenes with a wall that may tilt
  if (membrane_beads > 0) all.emplace_back("membrane", &membrane);  // scenes with a membrane
  if (clumps > 0)  // scenes without clumps keep their checkpoints' buffer list
    for (auto [name, b] : std::initializer_list<std::pair<std::string, Buffer*>>{
             {"clump_pos", &clump_pos}, {"clump_pos_lo", &clump_pos_lo},
             {"clump_quat", &clump_quat}, {"clump_vel", &clump_vel}, {"clump_mom", &clump_mom}})
      all.emplace_back(name, b);
  return all;
}

void State::grow_walls(const Model& model, int slots) {
  Device& d = model.device();
  wall_slots = slots;
  wall_spring = make(d, std::max<size_t>(16, size_t(slots) * model.config().history_bytes_per_contact()));
  wall_force = make(d, std::max<size_t>(16, size_t(slots) * 4 * model.real_size()));
}

std::vector<Buffer> State::share_views(const Model& model,
                                       std::initializer_list<size_t> sizes) {
  Device& d = model.device();
  const size_t align = d.base_align();
  std::vector<size_t> at;  // each view's offset, then the end of the last
  size_t end = 0;
  for (size_t b : sizes) {
    at.push_back((end + align - 1) / align * align);
    end = at.back() + std::max<size_t>(b, 16);
  }
  if (end > share.bytes) share = make(d, end + end / 16);
  std::vector<Buffer> views;
  size_t k = 0;
  for (size_t b : sizes) {
    views.push_back(Buffer{d.view(share.get(), at[k], std::max<size_t>(b, 16)), b});
    ++k;
  }
  return views;
}

State::ListScratch State::list_scratch(const Model& model) {
  std::vector<Buffer> v = share_views(model, {spring.bytes, nbr.bytes, nbr_upper.bytes});
  return {std::move(v[0]), std::move(v[1]), std::move(v[2])};
}

State::WallScratch State::wall_scratch(const Model& model) {
  std::vector<Buffer> v = share_views(model, {wall_near.bytes, wall_spring.bytes, wall_force.bytes});
  return {std::move(v[0]), std::move(v[1]), std::move(v[2])};
}

void State::grow_upper(const Model& model, int slots) {
  Device& d = model.device();
  up_slots = slots;
  nbr = make(d, std::max<size_t>(16, size_t(up_slots) * sizeof(int)));
  spring = make(d, spring_bytes(model));
}

void State::upper_scratch(const Model& model) {
  Device& d = model.device();
  share = make(d, share_bytes(model));
}

void State::grow_lower(const Model& model, int slots) {
  Device& d = model.device();
  lo_slots = slots;
  mirror = make(d, std::max<size_t>(16, size_t(lo_slots) * sizeof(int)));
}

void State::resize_lists(const Model& model, int up, int lo) {
  grow_upper(model, up);
  upper_scratch(model);
  grow_lower(model, lo);
}

// Per-contact history of the list slots (the planes the compiled slots
// declare, cl_program.h); a 16-byte stand-in when there is none.
size_t State::spring_bytes(const Model& model) const {
  return std::max<size_t>(16, size_t(up_slots) * model.config().history_bytes_per_contact());
}

}  // namespace simsols
