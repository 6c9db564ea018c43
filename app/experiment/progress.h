// Progress lines for long work, on stderr. On a terminal one line is
// redrawn; otherwise (CI logs, pipes) a fresh line is printed every few
// seconds.
//   Progress           a plain run: simulated time, steps, rate, ETA;
//   ProgrammeProgress  a test's loading programme (apparatus.h): the share
//                      of the whole programme done, where the test is, and
//                      an ETA over the programme and the work after it (the
//                      rest of a campaign).
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "solver/apparatus/apparatus.h"

namespace simsols {

// True at most once per `period` of wall time (lines of the preparation
// stages); elapsed() is the wall time since it was made, in seconds.
class Ticker {
 public:
  explicit Ticker(std::chrono::seconds period = std::chrono::seconds(10))
      : period_(period), start_(std::chrono::steady_clock::now()), next_(start_ + period) {}
  bool due() {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_) return false;
    next_ = now + period_;
    return true;
  }
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::seconds period_;
  std::chrono::steady_clock::time_point start_, next_;
};

// A specimen's preparation (preparation.h, tamping.h, expansion.h) has no
// checkpoint: stopped, it is started again by the same command.
struct PreparationStopped : std::exception {
  const char* what() const noexcept override {
    return "stopped while preparing the specimen (a preparation has no checkpoint: the same "
           "command prepares it again)";
  }
};

// What a preparation is handed: where its lines go, and its caller's wish
// to stop, which the preparation's loops ask between chunks of steps
// (check() throws PreparationStopped). A plain line function converts to
// one that never stops.
class PrepLog {
 public:
  using Line = std::function<void(const std::string&)>;
  PrepLog() = default;
  PrepLog(Line line, std::function<bool()> stop = {})
      : line_(std::move(line)), stop_(std::move(stop)) {}
  template <class F>
    requires std::is_invocable_v<const F&, const std::string&> &&
             (!std::is_same_v<std::decay_t<F>, PrepLog>)
  PrepLog(F f) : line_(std::move(f)) {}
  void operator()(const std::string& line) const {
    if (line_) line_(line);
  }
  void check() const {
    if (stop_ && stop_()) throw PreparationStopped();
  }
  // The same, each line after `head`.
  PrepLog with_head(std::string head) const {
    Line line = [inner = line_, head = std::move(head)](const std::string& l) {
      if (inner) inner(head + l);
    };
    return PrepLog(std::move(line), stop_);
  }
  explicit operator bool() const { return static_cast<bool>(line_); }

 private:
  Line line_;
  std::function<bool()> stop_;
};

class Progress {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;
  // `clock` (wall time for the rate and ETA) and `out` (where the lines go;
  // a terminal gets the redrawn line) are seams for tests.
  Progress(std::string label, std::int64_t total_steps, double dt, std::int64_t particles,
           bool quiet, Clock clock = std::chrono::steady_clock::now, std::FILE* out = stderr);
  void update(std::int64_t step, bool force = false);
  void finish(std::int64_t step);

 private:
  std::string line(std::int64_t step, bool final) const;
  std::string label_;
  std::int64_t total_, first_step_ = -1, particles_;
  double dt_;
  bool quiet_;
  Clock clock_;
  std::FILE* out_;
  bool tty_;
  std::chrono::steady_clock::time_point start_, last_;
};

class ProgrammeProgress {
 public:
  using Clock = Progress::Clock;
  // `later` is the particle-steps of the work after this test (0: none);
  // `particles` those of this test, to turn them into steps.
  ProgrammeProgress(std::string label, bool quiet, double later, std::int64_t particles,
                    Clock clock = std::chrono::steady_clock::now, std::FILE* out = stderr);
  // The programme as it is when this invocation starts (a resumed test has
  // steps done already: the rate counts only the steps run now).
  void start(const LoadingProgramme& test);
  // A line at most every 0.5 s on a terminal, 10 s elsewhere (or now with
  // `force`); `step` and `time` are the simulation's.
  void show(const LoadingProgramme& test, std::int64_t step, double time, bool force = false);
  // The last line: where the test ended and the wall time it took.
  void end(const LoadingProgramme& test, std::int64_t step, double time);

 private:
  double seconds() const;
  std::string eta(const LoadingProgramme& test) const;
  // "[label]  40.0%  status  step N  t = T s  " + tail (the ETA, or the duration)
  std::string line(const LoadingProgramme& test, std::int64_t step, double time,
                   const std::string& tail) const;
  std::string label_;
  bool quiet_;
  double later_;
  std::int64_t particles_;
  Clock clock_;
  std::FILE* out_;
  bool tty_;
  double first_done_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::optional<std::chrono::steady_clock::time_point> last_;
};

}  // namespace simsols
