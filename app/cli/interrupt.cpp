#include "app/cli/interrupt.h"

#include <unistd.h>

#include <atomic>

namespace simsols {
namespace {

// See interrupt.h: the one process-wide flag. Lock-free atomic, so that
// both the signal handler and the study's worker threads may touch it.
std::atomic<int> g_signal = 0;
static_assert(std::atomic<int>::is_always_lock_free);

void on_signal(int sig) {
  // A second Ctrl-C (someone at the keyboard) leaves now. A repeated
  // SIGTERM does not: a scheduler may send it to every process of a job
  // and the job script pass it on again (cluster.h), and the checkpoint
  // must still be written.
  if (g_signal != 0 && sig == SIGTERM) return;
  if (g_signal != 0) {  // the second one: leave now
    static const char msg[] = "\nsecond interrupt: exiting at once\n";
    [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, msg, sizeof msg - 1);
    _exit(128 + sig);
  }
  g_signal = sig;
  static const char msg[] =
      "\ninterrupted: finishing the current step, then writing the checkpoint (interrupt again "
      "to exit at once)\n";
  [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, msg, sizeof msg - 1);
}

}  // namespace

InterruptScope::InterruptScope() {
  g_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
}

InterruptScope::~InterruptScope() {
  sigaction(SIGINT, &old_int_, nullptr);
  // A command stopped by SIGTERM is on its way out: the repeated SIGTERM
  // on_signal ignores may still arrive after this scope, and must not end
  // the process before its last lines (stdout is buffered) are written.
  if (g_signal == SIGTERM) std::signal(SIGTERM, SIG_IGN);
  else sigaction(SIGTERM, &old_term_, nullptr);
}

bool InterruptScope::requested() const { return g_signal != 0; }
int InterruptScope::signal() const { return g_signal; }

}  // namespace simsols
