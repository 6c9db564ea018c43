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
#include <functional>
#include <optional>
#include <string>

#include "solver/apparatus/apparatus.h"
#include "solver/apparatus/specimen/prep_log.h"  // Ticker

namespace simsols {

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
