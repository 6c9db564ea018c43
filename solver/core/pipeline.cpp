#include "solver/core/pipeline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "solver/core/kernel_args.h"
#include "solver/kernels/layout.h"
#include "solver/core/observe.h"

namespace simsols {
namespace {

constexpr int kMaxNeighbors = 256;  // MAX_CAP in neighbors.cl

// Work items of the lane kernels (LANES particles each).
size_t lane_groups(const Model& m, int n) { return (n + m.config().lanes - 1) / m.config().lanes; }

void build_grid(const Model& m, State& s) {
  const Kernels& k = m.kernels();
  const Real inv_cell{1.0 / m.cell_size()};
  set_args(m, k.grid_clear, arg("count", s.cell_count), arg("table", s.table));
  launch_exact(m, k.grid_clear, s.table);
  set_args(m, k.grid_count, arg("pos", s.pos), arg("bucket", s.bucket), arg("slot", s.slot),
           arg("count", s.cell_count), arg("cell", s.cell), arg("inv_cell", inv_cell),
           arg("table", s.table), arg("n", s.n));
  launch(m, k.grid_count, s.n);
  set_args(m, k.scan_chunks, arg("count", s.cell_count), arg("chunk_sum", s.chunk_sum),
           arg("table", s.table), arg("chunk_len", s.chunk_len));
  launch_exact(m, k.scan_chunks, s.chunks);
  set_args(m, k.scan_totals, arg("chunk_sum", s.chunk_sum), arg("chunks", s.chunks));
  launch_exact(m, k.scan_totals, 1);
  set_args(m, k.scan_apply, arg("count", s.cell_count), arg("chunk_sum", s.chunk_sum),
           arg("start", s.cell_start), arg("table", s.table), arg("chunk_len", s.chunk_len));
  launch_exact(m, k.scan_apply, s.chunks);
  set_args(m, k.grid_scatter, arg("bucket", s.bucket), arg("slot", s.slot),
           arg("start", s.cell_start), arg("sorted", s.sorted), arg("n", s.n));
  launch(m, k.grid_scatter, s.n);
}

// Slots to allocate for `need`: 1/16 to spare, so that a slowly growing
// list does not reallocate at every rebuild.
int with_spare(std::uint32_t need) { return int(need + need / 16); }

// In-place exclusive prefix sum of `values` (entries 0..len-1), with the
// grid's scan kernels (grid.cl) and its chunk sums as scratch. Returns the
// last entry afterwards: with a 0 there, the sum of the others.
std::uint32_t prefix_sum(const Model& m, State& s, const Buffer& values, std::uint32_t len) {
  const Kernels& k = m.kernels();
  const std::uint32_t chunk_len = (len + s.chunks - 1) / s.chunks;
  set_args(m, k.scan_chunks, arg("count", values), arg("chunk_sum", s.chunk_sum), arg("table", len),
           arg("chunk_len", chunk_len));
  launch_exact(m, k.scan_chunks, s.chunks);
  set_args(m, k.scan_totals, arg("chunk_sum", s.chunk_sum), arg("chunks", s.chunks));
  launch_exact(m, k.scan_totals, 1);
  set_args(m, k.scan_apply, arg("count", values), arg("chunk_sum", s.chunk_sum),
           arg("start", values), arg("table", len), arg("chunk_len", chunk_len));
  launch_exact(m, k.scan_apply, s.chunks);
  std::uint32_t last = 0;
  m.device().read(values.get(), sizeof last, &last, size_t(len - 1) * sizeof last);
  return last;
}

// Lengths, then the slices' offsets (neighbors.cl). Returns the upper and
// lower slots the new lists need.
std::array<std::uint32_t, 2> size_lists(const Model& m, State& s) {
  const Kernels& k = m.kernels();
  set_args(m, k.count_neighbors, arg("pos", s.pos), arg("pos_lo", s.pos_lo),
           arg("count", s.cell_count), arg("start", s.cell_start), arg("sorted", s.sorted),
           arg("nbr_count", s.nbr_count), arg("nbr_upper", s.nbr_upper), arg("flags", s.flags),
           arg("body", m.body_buffer()), arg("cell", s.cell),
           arg("inv_cell", Real{1.0 / m.cell_size()}), arg("skin", Real{m.skin()}),
           arg("table", s.table), arg("n", s.n));
  launch(m, k.count_neighbors, s.n);
  int flags[FLAG_LONGEST_LIST + 1] = {};
  m.device().read(s.flags.get(), sizeof flags, flags);
  if (flags[FLAG_LONGEST_LIST] > kMaxNeighbors)
    throw DeviceError("a particle has " + std::to_string(flags[FLAG_LONGEST_LIST]) +
                      " neighbours within the skin (limit 256): reduce numerics.skin or the "
                      "size ratio");
  set_args(m, k.slice_widths, arg("nbr_count", s.nbr_count), arg("nbr_upper", s.nbr_upper),
           arg("up_width", s.up_off), arg("lo_width", s.lo_off), arg("n", s.n),
           arg("slices", s.slices));
  launch(m, k.slice_widths, s.slices + 1);
  return {prefix_sum(m, s, s.up_off, s.slices + 1), prefix_sum(m, s, s.lo_off, s.slices + 1)};
}

// The lists (neighbors.cl), laid out anew. The previous lists wait in
// `share` (list_scratch), at the old capacity's stride.
void build_lists(const Model& m, State& s) {
  const Kernels& k = m.kernels();
  const int old_stride = s.up_slots;
  State::ListScratch old = s.list_scratch(m);
  if (m.config().history_planes() > 0) m.device().copy(s.spring.get(), old.hist.get(), s.spring.bytes);
  m.device().copy(s.nbr.get(), old.nbr.get(), s.nbr.bytes);
  m.device().copy(s.nbr_upper.get(), old.upper.get(), s.nbr_upper.bytes);
  const std::array<std::uint32_t, 2> need = size_lists(m, s);
  const bool grow_up = need[0] > std::uint32_t(s.up_slots);
  if (grow_up) s.grow_upper(m, with_spare(need[0]));
  if (need[1] > std::uint32_t(s.lo_slots)) s.grow_lower(m, with_spare(need[1]));
  // slots the build leaves unwritten (a slice's padding, the spare tail)
  // hold zeros, not an older build's values: the state is the same however
  // it was reached (a resumed run hashes as the straight one)
  for (const Buffer* b : {&s.nbr, &s.spring, &s.mirror}) m.device().fill_zero(b->get(), b->bytes);
  set_args(m, k.build_neighbors, arg("pos", s.pos), arg("pos_lo", s.pos_lo),
           arg("count", s.cell_count), arg("start", s.cell_start), arg("sorted", s.sorted),
           arg("old_up_off", s.old_up_off), arg("old_upper", old.upper),
           arg("old_nbr", old.nbr), arg("old_hist", old.hist), arg("old_stride", old_stride),
           arg("up_off", s.up_off), arg("lo_off", s.lo_off), arg("nbr_upper", s.nbr_upper),
           arg("nbr", s.nbr), arg("mirror", s.mirror), arg("spring", s.spring),
           arg("stride", s.up_slots), arg("pos_build", s.pos_build), arg("body", m.body_buffer()),
           arg("cell", s.cell), arg("inv_cell", Real{1.0 / m.cell_size()}),
           arg("skin", Real{m.skin()}),
           arg("table", s.table), arg("n", s.n));
  launch(m, k.build_neighbors, s.n);
  old = {};  // the views go before share may be replaced
  if (grow_up) s.upper_scratch(m);
  set_args(m, k.build_mirrors, arg("nbr_count", s.nbr_count), arg("nbr_upper", s.nbr_upper),
           arg("up_off", s.up_off), arg("nbr", s.nbr), arg("lo_off", s.lo_off),
           arg("mirror", s.mirror), arg("n", s.n));
  launch(m, k.build_mirrors, s.n);
}

// The walls near each particle (walls.cl, broad phase), their slots laid
// out anew and carried over from the previous layout, and the walls'
// travel restarted with the lists.
void build_wall_slots(const Model& m, State& s) {
  if (!m.config().walls) return;
  const Kernels& k = m.kernels();
  const State::WallScratch old = s.wall_scratch(m);
  m.device().copy(s.wall_near.get(), old.near.get(), s.wall_near.bytes);
  m.device().copy(s.wall_spring.get(), old.spring.get(), s.wall_spring.bytes);
  m.device().copy(s.wall_force.get(), old.force.get(), s.wall_force.bytes);
  s.wall_off.mem.swap(s.old_wall_off.mem);
  set_args(m, k.build_wall_near, arg("pos", s.pos), arg("walls", m.wall_buffer()),
           arg("wall_point", s.wall_point), arg("wall_turn", s.wall_turn),
           arg("membrane", s.membrane), arg("wall_near", s.wall_near),
           arg("skin", Real{m.skin()}), arg("n", s.n), arg("nwalls", m.walls()));
  launch(m, k.build_wall_near, s.n);
  set_args(m, k.wall_widths, arg("wall_near", s.wall_near), arg("width", s.wall_off), arg("n", s.n),
           arg("slices", s.slices));
  launch(m, k.wall_widths, s.slices + 1);
  const std::uint32_t need = prefix_sum(m, s, s.wall_off, s.slices + 1);
  const int old_stride = s.wall_slots;
  const bool grow = need > std::uint32_t(s.wall_slots);
  if (grow) s.grow_walls(m, with_spare(need));
  for (const Buffer* b : {&s.wall_spring, &s.wall_force})  // as in build_lists
    m.device().fill_zero(b->get(), b->bytes);
  set_args(m, k.carry_wall_slots, arg("old_near", old.near), arg("old_off", s.old_wall_off),
           arg("old_spring", old.spring), arg("old_force", old.force),
           arg("old_stride", old_stride), arg("wall_near", s.wall_near),
           arg("wall_off", s.wall_off), arg("wall_spring", s.wall_spring),
           arg("wall_force", s.wall_force), arg("stride", s.wall_slots), arg("n", s.n),
           arg("nwalls", m.walls()));
  launch(m, k.carry_wall_slots, s.n);
  set_args(m, k.reset_wall_travel, arg("wall_point", s.wall_point), arg("nwalls", m.walls()));
  launch_exact(m, k.reset_wall_travel, m.walls());
}

// A periodic cell's particles back inside it (periodic.cl), before the grid.
void wrap_into_cell(const Model& m, State& s) {
  if (!m.config().periodic) return;
  const Kernels& k = m.kernels();
  set_args(m, k.wrap_positions, arg("pos", s.pos), arg("cell", s.cell), arg("n", s.n));
  launch(m, k.wrap_positions, s.n);
}

// Steps until the next look at the flags: the fastest particle, at twice
// its speed, must not cover the skin/4 that separates the rebuild trigger
// (skin/4) from the validity limit (skin/2).
std::int64_t check_interval(const Model& m, double vmax) {
  constexpr std::int64_t kMax = 64;
  if (!(vmax < 1e30)) return 1;  // NaN or infinite: the guard takes over (guard.h)
  if (vmax <= 0) return kMax;
  const double steps = 0.25 * m.skin() / (2.0 * vmax * m.dt());
  return std::clamp<std::int64_t>(static_cast<std::int64_t>(steps), 1, kMax);
}

}  // namespace

void request_rebuild(const Model& m, State& s) {
  const int rebuild = 1;
  m.device().write(s.flags.get(), sizeof rebuild, &rebuild, FLAG_REBUILD * sizeof(int));
  s.next_check = s.step;
}

void detect_contacts(const Model& m, State& s) {
  if (s.step < s.next_check) return;
  int flags[FLAG_RUNAWAY_FIRST + 1] = {};
  m.device().read(s.flags.get(), sizeof flags, flags);
  if (flags[FLAG_RUNAWAY_FIRST] != State::kNoRunaway) s.fault_seen = true;  // the runaway mark (guard.h)
  float v2 = 0;
  std::memcpy(&v2, &flags[FLAG_MAX_SPEED2], sizeof v2);
  if (flags[FLAG_LATE]) ++s.late_builds;
  s.next_check = s.step + check_interval(m, std::sqrt(double(v2)));
  const int zero[FLAG_LATE + 1] = {};  // the slots before the runaway mark
  if (flags[FLAG_REBUILD] || flags[FLAG_MAX_SPEED2] || flags[FLAG_LATE])
    m.device().write(s.flags.get(), sizeof zero, zero);
  if (!flags[FLAG_REBUILD]) return;

  wrap_into_cell(m, s);
  build_grid(m, s);
  // The offsets in use become the "old" ones the springs are carried from
  // (the rest of the previous lists: build_lists).
  s.up_off.mem.swap(s.old_up_off.mem);
  build_lists(m, s);
  build_wall_slots(m, s);
  cell_rebuilt(m, s);
  ++s.list_builds;
}

void contact_forces(const Model& m, State& s) {
  const Kernels& k = m.kernels();
  set_args(m, k.pair_forces, arg("pos", s.pos), arg("pos_lo", s.pos_lo), arg("vel", s.vel),
           arg("omega", s.omega), arg("up_off", s.up_off), arg("nbr", s.nbr),
           arg("nbr_upper", s.nbr_upper), arg("spring", s.spring), arg("pairs", m.pair_buffer()),
           arg("share", s.share), arg("force", s.force), arg("torque", s.torque),
           arg("body_offset", m.body_offset_buffer()), arg("contacts_last", s.touching),
           arg("cell", s.cell), arg("dt", Real{m.dt()}),
           arg("rolling_damping", Real{m.scene().effects.rolling_damping}),
           arg("stride", s.up_slots), arg("n", s.n), arg("nmat", m.pairs().n));
  launch(m, k.pair_forces, lane_groups(m, s.n));
}

void membrane_forces(const Model& m, State& s) {
  if (!m.config().membrane) return;
  const Kernels& k = m.kernels();
  set_args(m, k.membrane_forces, arg("pos", s.pos), arg("pos_lo", s.pos_lo), arg("vel", s.vel),
           arg("membrane", s.membrane), arg("membrane_force", s.membrane_force));
  launch(m, k.membrane_forces, size_t(s.membrane_beads));
}

void finish_particles(const Model& m, State& s) {
  const Kernels& k = m.kernels();
  const Effects& e = m.scene().effects;
  set_args(m, k.finish_particles, arg("pos", s.pos), arg("pos_lo", s.pos_lo), arg("vel", s.vel),
           arg("omega", s.omega), arg("force", s.force), arg("torque", s.torque),
           arg("pos_build", s.pos_build), arg("flags", s.flags),
           arg("groups_done", s.groups_done), arg("contacts_last", s.touching),
           arg("nbr_count", s.nbr_count), arg("nbr_upper", s.nbr_upper), arg("lo_off", s.lo_off),
           arg("mirror", s.mirror), arg("share", s.share), arg("walls", m.wall_buffer()),
           arg("wall_point", s.wall_point), arg("wall_point_lo", s.wall_point_lo),
           arg("wall_turn", s.wall_turn), arg("wall_vel", s.wall_vel), arg("wall_off", s.wall_off),
           arg("wall_spring", s.wall_spring), arg("wall_force", s.wall_force),
           arg("wall_stride", s.wall_slots), arg("pairs", m.pair_buffer()),
           arg("wall_touch", s.wall_touch), arg("wall_near", s.wall_near), arg("servo", s.servo),
           arg("wall_partial", s.wall_partial), arg("wall_reaction", s.wall_reaction),
           arg("wall_mean", s.wall_mean), arg("body_offset", m.body_offset_buffer()),
           arg("membrane", s.membrane), arg("membrane_force", s.membrane_force),
           arg("cell", s.cell), arg("gravity", gravity_arg(m)),
           arg("fluid", fluid_arg(m)), arg("fluid_viscosity", Real{e.fluid_params.viscosity}),
           arg("dt", Real{m.dt()}), arg("rolling_damping", Real{e.rolling_damping}),
           arg("skin", Real{m.skin()}), arg("stride", s.up_slots), arg("n", s.n),
           arg("nwalls", m.walls()), arg("nmat", m.pairs().n), arg("wall_chunk", kWallChunk),
           arg("wall_groups", wall_chunks(s)));
  launch(m, k.finish_particles, lane_groups(m, s.n));
}

void move_clumps(const Model& m, State& s) {
  if (!m.config().clumps) return;
  const Kernels& k = m.kernels();
  set_args(m, k.move_clumps, arg("pos", s.pos), arg("pos_lo", s.pos_lo), arg("vel", s.vel),
           arg("omega", s.omega), arg("force", s.force), arg("torque", s.torque),
           arg("pos_build", s.pos_build), arg("flags", s.flags),
           arg("body_offset", m.body_offset_buffer()), arg("clump_inertia", m.clump_buffer()),
           arg("clump_members", m.clump_member_buffer()), arg("clump_pos", s.clump_pos),
           arg("clump_pos_lo", s.clump_pos_lo), arg("clump_quat", s.clump_quat),
           arg("clump_vel", s.clump_vel), arg("clump_mom", s.clump_mom),
           arg("gravity", gravity_arg(m)), arg("dt", Real{m.dt()}), arg("skin", Real{m.skin()}),
           arg("nclumps", m.clumps()));
  launch(m, k.move_clumps, m.clumps());
}

void move_walls(const Model& m, State& s) {
  if (!m.config().walls) return;
  const Kernels& k = m.kernels();
  if (m.config().servo_in_finish()) return;  // finish_particles moved them (CPUs)
  if (m.config().servo) {
    const int groups = static_cast<int>(reduce_wall_forces(m, s));
    set_args(m, k.servo_walls, arg("walls", m.wall_buffer()), arg("servo", s.servo),
             arg("partial", s.wall_partial), arg("wall_vel", s.wall_vel),
             arg("reading", s.wall_reaction), arg("mean", s.wall_mean),
             arg("wall_point", s.wall_point), arg("wall_point_lo", s.wall_point_lo),
             arg("wall_turn", s.wall_turn), arg("flags", s.flags), arg("dt", Real{m.dt()}),
             arg("skin", Real{m.skin()}), arg("groups", groups), arg("nwalls", m.walls()));
    launch_exact(m, k.servo_walls, 1);
  } else {
    set_args(m, k.advance_walls, arg("wall_point", s.wall_point),
             arg("wall_point_lo", s.wall_point_lo), arg("wall_vel", s.wall_vel),
             arg("flags", s.flags), arg("dt", Real{m.dt()}), arg("skin", Real{m.skin()}),
             arg("nwalls", m.walls()));
    launch_exact(m, k.advance_walls, m.walls());
  }
}

int wall_chunks(const State& s) { return std::max(1, (s.n + kWallChunk - 1) / kWallChunk); }

size_t reduce_wall_forces(const Model& m, State& s) {
  const Kernels& k = m.kernels();
  const int chunks = wall_chunks(s);
  set_args(m, k.reduce_walls, arg("wall_near", s.wall_near), arg("wall_off", s.wall_off),
           arg("wall_force", s.wall_force), arg("partial", s.wall_partial), arg("pos", s.pos),
           arg("walls", m.wall_buffer()), arg("wall_point", s.wall_point),
           arg("wall_turn", s.wall_turn), arg("n", s.n), arg("chunk", kWallChunk),
           arg("chunks", chunks), arg("nwalls", m.walls()));
  launch(m, k.reduce_walls, size_t(chunks));
  return static_cast<size_t>(chunks);
}

void derive_state(const Model& m, State& s) {
  read_cell(m, s);
  if (!m.config().shared_rolling_cap()) return;  // `touching` unused
  const std::vector<double> f = read_reals(m, s.force, size_t(s.n) * 4);
  std::vector<int> count(s.n);
  for (int i = 0; i < s.n; ++i) count[i] = static_cast<int>(f[4 * size_t(i) + 3]);
  m.device().write(s.touching.get(), count.size() * sizeof(int), count.data());
}

void step(const Model& m, State& s) {
  detect_contacts(m, s);
  contact_forces(m, s);
  membrane_forces(m, s);
  finish_particles(m, s);
  move_clumps(m, s);
  move_walls(m, s);
  move_cell(m, s);
  ++s.step;
  s.time = s.step * m.dt();
}

}  // namespace simsols
