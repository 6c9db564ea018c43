// The executable's tests run shell commands and read what they print:
// one helper for test_cli and test_cli_errors.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace simsols::testing {

struct CliResult {
  int status = -1;  // exit status; -1 when the command did not exit normally
  std::string out;  // stdout and stderr together
};

// Runs `cmd` with /bin/sh, stderr folded into stdout.
inline CliResult shell(const std::string& cmd) {
  CliResult r;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int s = pclose(p);
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

}  // namespace simsols::testing
