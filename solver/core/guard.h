// Guard: a run that goes wrong stops at its first bad step (stability case 10).
//
// Every step, integrate.cl marks a particle whose new state is not finite,
// or which moved more than a tenth of its radius in that one step: no
// contact can be resolved at that speed (its overlap would jump by ten
// times the 1 % a resolved contact reaches), so the run is no longer a DEM
// computation but a runaway. A time step forced far above the limit does
// this within a few hundred steps; a 10 m/s impact at the default step
// moves a bead by 0.15 % of its radius per step (test_guard.cpp). (A bead
// outrunning its neighbour list, moved beyond skin/2, is a different
// check: it is counted in State::late_builds and reported as a warning.)
// The mark is the lowest such index and what was wrong
// (flags[4], flags[5]).
//
// The host does not read the mark every step, which would stall a GPU.
// Instead the Guard keeps, on the device, a copy of the dynamic state taken
// every `interval` steps (only after reading the mark clear), and a log of
// what the host wrote into the state since (wall velocities, servo
// settings, restarted means). The mark is read
//   - at every neighbour-list check (detect_contacts reads the flags anyway),
//   - before the next copy,
//   - before the host takes any reading (observe, snapshot, wall means,
//     checkpoints), so no output ever holds a bad value.
// When it is found set, the Guard restores the copy and replays the steps
// and the logged writes one at a time, reading the mark after each, to find
// the first step that sets it; it then restores and replays again up to the
// step before, and throws RunawayError naming the step, the particle and
// what went wrong. The Simulation is left at that last good state: the
// caller saves it as a checkpoint and stops (`simsols run`:
// fault_checkpoint.bin, exit status 4). Replays give the same numbers as
// the run because a step is deterministic (tests/solver/core/test_determinism.cpp).
//
// Cost: device memory for one more copy of the dynamic buffers
// (backup_bytes()), one device-side copy and one 8-byte read per interval.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/core/model.h"
#include "solver/core/state.h"

namespace simsols {

struct Fault {
  std::int64_t step = 0;     // the step that produced the bad state (the state's step after it)
  double time = 0;           // s, at the end of that step
  int particle = -1;         // lowest index marked in that step
  int marked = 0;            // particles marked in that step
  bool non_finite = false;   // else: moved too far in one step
  Vec3 position{};           // of the particle after the bad step, absolute, m
  Vec3 velocity{};           // m/s, after the bad step
  double moved = 0;          // m, its displacement in that step
  double limit = 0;          // m, a tenth of its radius
  bool located = true;       // false: the replay did not reproduce the mark
  std::string describe() const;
};

class RunawayError : public std::runtime_error {
 public:
  explicit RunawayError(const Fault& fault);
  const Fault& fault() const { return fault_; }

 private:
  Fault fault_;
};

class Guard {
 public:
  static constexpr std::int64_t kDefaultInterval = 1000;

  Guard(const Model& model, State& state);

  // Steps between copies (> 0).
  void set_interval(std::int64_t steps);
  std::int64_t interval() const { return interval_; }

  // After each step of a run: copies the state when due, and resolves a
  // mark that detect_contacts saw. Throws RunawayError.
  void after_step();
  // Before the host reads anything out of the state: reads the mark now.
  void before_reading();
  // A host write into a state buffer, logged so that a replay repeats it.
  void write(Buffer State::*buffer, size_t offset, const void* data, size_t bytes);
  // Has the neighbour lists and wall slots rebuilt at the next step (after
  // a host write they no longer cover: request_rebuild, pipeline.h), logged
  // so that a replay asks at this step too.
  void rebuild_lists();
  // After the state was replaced wholesale (a checkpoint loaded): a fresh copy.
  void reset();

  size_t backup_bytes() const;

 private:
  struct Logged {
    std::int64_t step;
    Buffer State::*buffer;  // nullptr: a list rebuild asked for (rebuild_lists)
    size_t offset;
    std::vector<unsigned char> data;
  };
  struct Mark {
    int particle = State::kNoRunaway;
    int what = 0;
    int count = 0;
    bool set() const { return particle != State::kNoRunaway; }
  };
  Mark read_mark();
  void clear_mark();
  void take_copy();
  void restore_copy();
  // The logged writes made at the current step, from log_[*next] on.
  void apply_logged(size_t* next);
  void replay_to(std::int64_t step);  // from the restored copy, with the logged writes
  [[noreturn]] void resolve();
  // A fault the replay could not place: what the mark said when it was seen.
  [[noreturn]] void throw_unlocated(const Mark& seen, std::int64_t seen_at);

  const Model& model_;
  State& state_;
  std::int64_t interval_ = kDefaultInterval;
  bool have_copy_ = false;
  std::int64_t copy_step_ = 0;
  double copy_time_ = 0;
  std::int64_t copy_list_builds_ = 0, copy_next_check_ = 0, copy_late_builds_ = 0;
  int copy_up_ = 0, copy_lo_ = 0, copy_walls_ = 0;  // list and wall-slot capacities of the copy
  std::vector<Buffer> copy_;
  std::vector<Logged> log_;
};

}  // namespace simsols
