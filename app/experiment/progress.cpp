#include "app/experiment/progress.h"

#include <unistd.h>

#include <cstdio>

#include "app/experiment/run_cost.h"

namespace simsols {
namespace {

// One progress line: on a terminal it redraws the current line (and ends it
// when `final`), elsewhere it is a line of its own.
void print_line(std::FILE* out, bool tty, const std::string& text, bool final) {
  if (tty) std::fprintf(out, final ? "\r%s\033[K\n" : "\r%s\033[K", text.c_str());
  else std::fprintf(out, "%s\n", text.c_str());
  std::fflush(out);
}

}  // namespace

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
  print_line(out_, tty_, line(step, false), false);
}

void Progress::finish(std::int64_t step) {
  if (quiet_) return;
  if (first_step_ < 0) first_step_ = step;
  print_line(out_, tty_, line(step, true), true);
}

ProgrammeProgress::ProgrammeProgress(std::string label, bool quiet, double later,
                                     std::int64_t particles, Clock clock, std::FILE* out)
    : label_(std::move(label)), quiet_(quiet), later_(later), particles_(particles),
      clock_(std::move(clock)), out_(out), tty_(isatty(fileno(out)) != 0), start_(clock_()) {}

void ProgrammeProgress::start(const LoadingProgramme& test) {
  first_done_ = test.step_count().done;
  start_ = clock_();
}

std::string ProgrammeProgress::line(const LoadingProgramme& test, std::int64_t step, double time,
                                    const std::string& tail) const {
  char buf[320];
  std::snprintf(buf, sizeof buf, "[%s] %5.1f%%  %s  step %lld  t = %.4f s  %s", label_.c_str(),
                100 * test.progress(), test.status().c_str(), static_cast<long long>(step), time,
                tail.c_str());
  return buf;
}

double ProgrammeProgress::seconds() const {
  return std::chrono::duration<double>(clock_() - start_).count();
}

// At the rate of this invocation, once it means something (2 s of stepping).
std::string ProgrammeProgress::eta(const LoadingProgramme& test) const {
  const LoadingProgramme::StepCount c = test.step_count();
  const double ran = c.done - first_done_, wall = seconds();
  if (!(ran > 0 && wall > 2)) return "ETA --";
  const double per_step = wall / ran;
  const double left = (c.total - c.done) * per_step;
  if (later_ <= 0) return "ETA " + human_seconds(left);
  const double after = later_ * per_step / double(particles_);
  return "ETA " + human_seconds(left + after) + " (this test " + human_seconds(left) + ")";
}

void ProgrammeProgress::show(const LoadingProgramme& test, std::int64_t step, double time,
                             bool force) {
  if (quiet_) return;
  const auto now = clock_();
  if (!force && last_ &&
      std::chrono::duration<double>(now - *last_).count() < (tty_ ? 0.5 : 10.0))
    return;
  last_ = now;
  print_line(out_, tty_, line(test, step, time, eta(test)), false);
}

void ProgrammeProgress::end(const LoadingProgramme& test, std::int64_t step, double time) {
  if (quiet_) return;
  print_line(out_, tty_, line(test, step, time, "in " + human_seconds(seconds())), true);
}

}  // namespace simsols
