// What a specimen's preparation (preparation.h, tamping.h, expansion.h)
// is handed and tells: a Ticker for its progress lines, PrepLog (where the
// lines go and whether its caller wants it to stop) and PreparationStopped.
#pragma once

#include <chrono>
#include <exception>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>

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

}  // namespace simsols
