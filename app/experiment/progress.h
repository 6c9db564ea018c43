// Progress line for long work: simulated time, steps, rate and ETA on
// stderr. On a terminal it redraws one line; otherwise (CI logs, pipes) it
// prints a fresh line every few seconds.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

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

}  // namespace simsols
