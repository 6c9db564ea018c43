#include "solver/core/guard.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "solver/core/observe.h"
#include "solver/core/pipeline.h"
#include "solver/kernels/layout.h"

namespace simsols {

std::string Fault::describe() const {
  char buf[768];
  const char* what = non_finite ? "its state became NaN or infinite"
                                : "it moved more than a tenth of its radius in one step";
  if (!located) {
    std::snprintf(buf, sizeof buf,
                  "runaway detected at step %lld (t = %.6g s): particle %d, %s; replaying from "
                  "the last copy did not reproduce it",
                  static_cast<long long>(step), time, particle, what);
    return buf;
  }
  std::snprintf(buf, sizeof buf,
                "runaway at step %lld (t = %.6g s): particle %d, %s (moved %.3g m in that step, "
                "limit %.3g m; velocity (%.4g, %.4g, %.4g) m/s at (%.6g, %.6g, %.6g) "
                "m); %d particle(s) marked in that step. %s",
                static_cast<long long>(step), time, particle, what, moved, limit, velocity[0],
                velocity[1], velocity[2], position[0], position[1], position[2], marked,
                non_finite ? "A NaN comes from a NaN or infinite input (a wall velocity, a servo "
                             "setting) or from a run that went unstable"
                           : "The time step is too large for the stiffness (numerics.dt, "
                             "dt_fraction, force_dt), or the scene starts far from equilibrium");
  return buf;
}

RunawayError::RunawayError(const Fault& fault)
    : std::runtime_error(fault.describe()), fault_(fault) {}

Guard::Guard(const Model& model, State& state) : model_(model), state_(state) {}

void Guard::set_interval(std::int64_t steps) {
  if (steps <= 0) throw std::invalid_argument("Guard::set_interval: steps must be > 0");
  interval_ = steps;
}

Guard::Mark Guard::read_mark() {
  static_assert(FLAG_RUNAWAY_WHAT == FLAG_RUNAWAY_FIRST + 1 &&
                FLAG_RUNAWAY_COUNT == FLAG_RUNAWAY_FIRST + 2);
  int v[3] = {0, 0, 0};  // FLAG_RUNAWAY_FIRST, _WHAT, _COUNT
  model_.device().read(state_.flags.get(), sizeof v, v, FLAG_RUNAWAY_FIRST * sizeof(int));
  Mark m;
  m.particle = v[0];
  m.what = v[1];
  m.count = v[2];
  return m;
}

void Guard::clear_mark() {
  const int clear[3] = {State::kNoRunaway, 0, 0};
  model_.device().write(state_.flags.get(), sizeof clear, clear, FLAG_RUNAWAY_FIRST * sizeof(int));
  state_.fault_seen = false;
}

void Guard::take_copy() {
  auto buffers = state_.dynamic_buffers();
  if (copy_.size() != buffers.size()) copy_.resize(buffers.size());
  for (size_t k = 0; k < buffers.size(); ++k) {
    const Buffer& b = *buffers[k].second;
    if (copy_[k].bytes != b.bytes || !copy_[k].get()) {
      copy_[k].mem = model_.device().alloc(b.bytes);
      copy_[k].bytes = b.bytes;
    }
    model_.device().copy(b.get(), copy_[k].get(), b.bytes);
  }
  copy_step_ = state_.step;
  copy_time_ = state_.time;
  copy_list_builds_ = state_.list_builds;
  copy_next_check_ = state_.next_check;
  copy_late_builds_ = state_.late_builds;
  copy_up_ = state_.up_slots;
  copy_lo_ = state_.lo_slots;
  copy_walls_ = state_.wall_slots;
  have_copy_ = true;
  log_.clear();
}

void Guard::restore_copy() {
  state_.resize_slots(model_, copy_up_, copy_lo_, copy_walls_);
  auto buffers = state_.dynamic_buffers();
  for (size_t k = 0; k < buffers.size(); ++k)
    model_.device().copy(copy_[k].get(), buffers[k].second->get(), copy_[k].bytes);
  state_.step = copy_step_;
  state_.time = copy_time_;
  state_.list_builds = copy_list_builds_;
  state_.next_check = copy_next_check_;
  state_.late_builds = copy_late_builds_;
  state_.fault_seen = false;
  derive_state(model_, state_);
}

void Guard::apply_logged(size_t* next) {
  while (*next < log_.size() && log_[*next].step == state_.step) {
    const Logged& l = log_[(*next)++];
    if (!l.buffer) request_rebuild(model_, state_);
    else model_.device().write((state_.*l.buffer).get(), l.data.size(), l.data.data(), l.offset);
    if (l.buffer == &State::cell) read_cell(model_, state_);  // the host's mirror of it
  }
}

void Guard::replay_to(std::int64_t target) {
  size_t next = 0;
  for (;;) {
    apply_logged(&next);
    if (state_.step >= target) break;
    step(model_, state_);
  }
}

void Guard::reset() {
  clear_mark();
  take_copy();
}

size_t Guard::backup_bytes() const {
  size_t total = 0;
  for (const Buffer& b : copy_) total += b.bytes;
  return total;
}

void Guard::after_step() {
  if (state_.fault_seen) resolve();
  if (!have_copy_ || state_.step - copy_step_ >= interval_) {
    if (read_mark().set()) resolve();
    take_copy();
  }
}

void Guard::before_reading() {
  if (state_.fault_seen || read_mark().set()) resolve();
}

void Guard::write(Buffer State::*buffer, size_t offset, const void* data, size_t bytes) {
  // A mark already set must be resolved before the write changes what a
  // replay would have to repeat.
  before_reading();
  Logged l{state_.step, buffer, offset, {}};
  l.data.assign(static_cast<const unsigned char*>(data),
                static_cast<const unsigned char*>(data) + bytes);
  model_.device().write((state_.*buffer).get(), bytes, data, offset);
  log_.push_back(std::move(l));
}

void Guard::rebuild_lists() {
  before_reading();
  request_rebuild(model_, state_);
  log_.push_back(Logged{state_.step, nullptr, 0, {}});
}

void Guard::throw_unlocated(const Mark& seen, std::int64_t seen_at) {
  Fault f;
  f.located = false;
  f.step = seen_at;
  f.time = state_.time;
  f.particle = seen.particle;
  f.non_finite = (seen.what & 1) != 0;
  f.marked = seen.count;
  if (have_copy_) {  // the state stays usable: clear the mark, copy it afresh
    clear_mark();
    take_copy();
  }
  throw RunawayError(f);
}

void Guard::resolve() {
  const std::int64_t seen_at = state_.step;
  const Mark seen = read_mark();
  if (!have_copy_) throw_unlocated(seen, seen_at);
  // Find the first step that sets the mark.
  restore_copy();
  size_t next = 0;
  Fault f;
  while (true) {
    if (state_.step >= seen_at) throw_unlocated(seen, seen_at);
    apply_logged(&next);
    step(model_, state_);
    const Mark m = read_mark();
    if (m.set()) {
      f.step = state_.step;
      f.time = state_.time;
      f.particle = m.particle;
      f.non_finite = (m.what & 1) != 0;
      f.marked = m.count;
      break;
    }
  }
  {
    const ParticleSnapshot q = download(model_, state_);
    f.position = q.position[f.particle];
    f.limit = 0.1 * q.radius[f.particle];
    f.velocity = q.velocity[f.particle];
    f.moved = norm(f.velocity) * model_.dt();  // the leapfrog's half-step velocity x dt
  }
  // Back to the state just before it (with the host's writes made then).
  restore_copy();
  replay_to(f.step - 1);
  clear_mark();
  take_copy();
  throw RunawayError(f);
}

}  // namespace simsols
