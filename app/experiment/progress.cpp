#include "app/experiment/progress.h"

#include <unistd.h>

#include <cstdio>

#include "app/experiment/run_cost.h"

namespace simsols {

Progress::Progress(std::string label, std::int64_t total_steps, double dt, std::int64_t particles,
                   bool quiet, Clock clock, std::FILE* out)
    : label_(std::move(label)), total_(total_steps), particles_(particles), dt_(dt), quiet_(quiet),
      clock_(std::move(clock)), out_(out), tty_(isatty(fileno(out)) != 0), start_(clock_()),
      last_(start_) {}

std::string Progress::line(std::int64_t step, bool final) const {
  const double wall = std::chrono::duration<double>(clock_() - start_).count();
  const double done = static_cast<double>(step - first_step_);
  const double rate = wall > 0 ? done / wall : 0;
  // No ETA until the rate means something (2 s of stepping); the last line
  // says how long the run took instead.
  std::string tail = "ETA --";
  if (final) tail = "in " + human_seconds(wall);
  else if (wall > 2 && rate > 0) tail = "ETA " + human_seconds((total_ - step) / rate);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "[%s] t = %.4e / %.4e s  step %lld/%lld (%.1f%%)  %.3g steps/s  %.3g particle-steps/s  %s",
                label_.c_str(), step * dt_, total_ * dt_, static_cast<long long>(step),
                static_cast<long long>(total_), total_ > 0 ? 100.0 * step / total_ : 100.0, rate,
                rate * particles_, tail.c_str());
  return buf;
}

void Progress::update(std::int64_t step, bool force) {
  if (first_step_ < 0) { first_step_ = step; start_ = clock_(); }
  if (quiet_) return;
  const auto now = clock_();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (!force && since < (tty_ ? 0.5 : 5.0)) return;
  last_ = now;
  if (tty_) std::fprintf(out_, "\r%s\033[K", line(step, false).c_str());
  else std::fprintf(out_, "%s\n", line(step, false).c_str());
  std::fflush(out_);
}

void Progress::finish(std::int64_t step) {
  if (quiet_) return;
  if (first_step_ < 0) first_step_ = step;
  std::fprintf(out_, tty_ ? "\r%s\033[K\n" : "%s\n", line(step, true).c_str());
}

}  // namespace simsols
