// The progress line (app/experiment/progress.h) for given inputs, on a clock
// the test moves by hand: steps and simulated time of the whole programme,
// the rate since this session's first step, the ETA of the steps left to
// the programme's end, and how often a line is printed (every 5 s into a
// file or pipe, every 0.5 s redrawn on a terminal).
#include <gtest/gtest.h>
#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/experiment/progress.h"

namespace simsols {
namespace {

using namespace std::chrono_literals;

// A clock that moves only when told.
struct FakeClock {
  std::chrono::steady_clock::time_point now{};
  void advance(double seconds) {
    now += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(seconds));
  }
  Progress::Clock clock() {
    return [this] { return now; };
  }
};

// What a Progress writes to a file, read back as it grows.
class FileSink {
 public:
  FileSink() : f_(std::tmpfile()) {}
  ~FileSink() { std::fclose(f_); }
  std::FILE* file() { return f_; }
  std::string take() {
    std::fflush(f_);
    std::string out;
    char buf[512];
    std::fseek(f_, static_cast<long>(read_), SEEK_SET);
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, f_)) > 0;) out.append(buf, n);
    read_ += out.size();
    std::fseek(f_, 0, SEEK_END);
    return out;
  }

 private:
  std::FILE* f_;
  size_t read_ = 0;
};

// A resumed programme of 10000 steps of 2 us with 324 beads: resumed at step
// 4000, 1000 steps in 10 s are 100 steps/s (3.24e4 particle-steps/s), and
// the 5000 steps left to the programme's end take 50 s.
TEST(Progress, LineGivesStepsTimeRateAndEtaOfTheWholeProgramme) {
  FakeClock c;
  FileSink out;
  Progress p("run", 10000, 2e-6, 324, false, c.clock(), out.file());
  p.update(4000);
  EXPECT_EQ(out.take(), "") << "nothing in the first 5 s";
  c.advance(10);
  p.update(5000);
  EXPECT_EQ(out.take(),
            "[run] t = 1.0000e-02 / 2.0000e-02 s  step 5000/10000 (50.0%)  100 steps/s  "
            "3.24e+04 particle-steps/s  ETA 50 s\n");
  c.advance(100);
  p.update(9000);  // 5000 steps in 110 s, 1000 left: 22 s
  EXPECT_EQ(out.take(),
            "[run] t = 1.8000e-02 / 2.0000e-02 s  step 9000/10000 (90.0%)  45.5 steps/s  "
            "1.47e+04 particle-steps/s  ETA 22 s\n");
}

// The rate needs 2 s of stepping before it gives an ETA; the last line says
// how long the session took instead.
TEST(Progress, NoEtaBeforeTwoSecondsAndDurationAtTheEnd) {
  FakeClock c;
  FileSink out;
  Progress p("shear", 1000000, 1e-7, 10, false, c.clock(), out.file());
  p.update(0);
  c.advance(1.5);
  p.update(300, true);
  EXPECT_NE(
      out.take().find("step 300/1000000 (0.0%)  200 steps/s  2e+03 particle-steps/s  ETA --\n"),
      std::string::npos);
  c.advance(1);
  p.update(500, true);  // 200 steps/s; 999500 steps left: 83.3 min
  EXPECT_NE(out.take().find("  200 steps/s  2e+03 particle-steps/s  ETA 83.3 min\n"),
            std::string::npos);
  c.advance(7497.5);  // 7500 s in all
  p.finish(1000000);
  EXPECT_EQ(out.take(),
            "[shear] t = 1.0000e-01 / 1.0000e-01 s  step 1000000/1000000 (100.0%)  133 steps/s  "
            "1.33e+03 particle-steps/s  in 2.1 h\n");
}

// Into a file, a line every 5 s at most (unless forced); quiet prints none.
TEST(Progress, FileGetsALineEveryFiveSeconds) {
  FakeClock c;
  FileSink out, none;
  Progress p("run", 100, 1e-6, 1, false, c.clock(), out.file());
  Progress q("run", 100, 1e-6, 1, true, c.clock(), none.file());
  int lines = 0;
  for (int s = 1; s <= 12; ++s) {  // one step a second for 12 s
    c.advance(1);
    p.update(s);
    q.update(s, true);
    const std::string got = out.take();
    if (!got.empty()) {
      ++lines;
      EXPECT_TRUE(s == 5 || s == 10) << "a line at " << s << " s: " << got;
    }
  }
  EXPECT_EQ(lines, 2);
  p.update(12, true);
  EXPECT_NE(out.take().find("step 12/100"), std::string::npos) << "forced";
  q.finish(12);
  EXPECT_EQ(none.take(), "");
}

// On a terminal one line is redrawn (\r ... erase to end of line), at most
// every 0.5 s; the last one ends the line.
TEST(Progress, TerminalRedrawsOneLine) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(grantpt(master), 0);
  ASSERT_EQ(unlockpt(master), 0);
  const int slave = open(ptsname(master), O_RDWR | O_NOCTTY);
  ASSERT_GE(slave, 0);
  termios raw{};
  tcgetattr(slave, &raw);
  cfmakeraw(&raw);  // bytes as written (no \n to \r\n)
  tcsetattr(slave, TCSANOW, &raw);
  std::FILE* tty = fdopen(slave, "w");
  auto read_master = [&] {
    std::fflush(tty);
    std::string got;
    char buf[1024];
    fcntl(master, F_SETFL, O_NONBLOCK);
    for (ssize_t n; (n = read(master, buf, sizeof buf)) > 0;) got.append(buf, size_t(n));
    return got;
  };
  FakeClock c;
  Progress p("run", 100, 1e-6, 1, false, c.clock(), tty);
  c.advance(0.3);
  p.update(1);
  EXPECT_EQ(read_master(), "") << "0.3 s after the start";
  c.advance(0.3);
  p.update(2);
  const std::string line = read_master();
  EXPECT_EQ(line.substr(0, 7), "\r[run] ");
  EXPECT_EQ(line.substr(line.size() - 3), "\033[K");
  c.advance(0.3);
  p.update(3);
  EXPECT_EQ(read_master(), "") << "0.3 s after the last line";
  p.finish(3);
  const std::string last = read_master();
  EXPECT_EQ(last.substr(last.size() - 4), "\033[K\n");
  std::fclose(tty);
  close(master);
}

// A loading programme the test sets by hand (apparatus.h).
class FakeProgramme : public LoadingProgramme {
 public:
  StepCount count;
  bool advance(std::int64_t) override { return false; }
  bool done() const override { return false; }
  const char* stage_name() const override { return "shear"; }
  bool measuring() const override { return true; }
  StepCount step_count() const override { return count; }
  std::string status() const override { return "shear dx = 1.000/3.000 mm"; }
  std::string caption() const override { return ""; }
  std::string save_state() const override { return ""; }
  void restore_state(const std::string&) override {}
};

// A test resumed at 2000 of 10000 programme steps, with a campaign's
// 1.0e6 particle-steps after it (100 beads: 10000 steps): 2000 steps in
// 10 s are 5 ms a step, so 6000 left take 30 s and the campaign 50 s more.
TEST(ProgrammeProgress, EtaCoversTheProgrammeAndTheWorkAfterIt) {
  FakeClock c;
  FileSink out;
  FakeProgramme test;
  test.count = {2000, 10000};
  ProgrammeProgress p("campaign 1/2 d3mm", false, 1.0e6, 100, c.clock(), out.file());
  p.start(test);
  p.show(test, 2000, 0.01);
  EXPECT_EQ(out.take(),
            "[campaign 1/2 d3mm]  20.0%  shear dx = 1.000/3.000 mm  step 2000  t = 0.0100 s  "
            "ETA --\n")
      << "the first line at once, no ETA before a rate";
  c.advance(10);
  test.count = {4000, 10000};
  p.show(test, 4000, 0.02);
  EXPECT_EQ(out.take(),
            "[campaign 1/2 d3mm]  40.0%  shear dx = 1.000/3.000 mm  step 4000  t = 0.0200 s  "
            "ETA 80 s (this test 30 s)\n");
  c.advance(5);
  test.count = {5000, 10000};
  p.show(test, 5000, 0.025);
  EXPECT_EQ(out.take(), "") << "into a file, at most a line every 10 s";
  p.end(test, 5000, 0.025);
  EXPECT_EQ(out.take(),
            "[campaign 1/2 d3mm]  50.0%  shear dx = 1.000/3.000 mm  step 5000  t = 0.0250 s  "
            "in 15 s\n");
}

}  // namespace
}  // namespace simsols
