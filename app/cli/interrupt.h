// Ctrl-C and kill for long commands (run, campaign, study).
//
// While an InterruptScope lives, SIGINT and SIGTERM do not end the process:
// they set a flag that the command's loop reads between steps. The command
// then finishes the step it is in, writes its checkpoint and the rows it
// measured, prints how to resume, and exits with 128 + the signal (130 for
// Ctrl-C, 143 for kill). A second Ctrl-C while it does that ends the
// process at once with the same status (the previous checkpoint stays
// loadable: every file is written to a temporary name and renamed); a
// repeated SIGTERM is ignored (a batch scheduler may send it twice: to the
// job's processes and through its script), also after the scope, while the
// command returns and the process exits.
//
// The flag is the one piece of process-wide state in the program: a signal
// handler can reach nothing else. Code below the command sees it only as
// the `stop_requested` function it is handed.
#pragma once

#include <csignal>
#include <functional>

namespace simsols {

class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

  bool requested() const;
  int signal() const;                             // 0 until one arrived
  int exit_status() const { return 128 + signal(); }
  std::function<bool()> stop_function() const {  // for the loops below the command
    return [this] { return requested(); };
  }

 private:
  struct sigaction old_int_{}, old_term_{};
};

}  // namespace simsols
