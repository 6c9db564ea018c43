#include "commands.h"
namespace simsols {
CommandRunner add_bench_command(CLI::App& app) {
  app.add_subcommand("bench", "Benchmark (not yet)");
  return [] { return 0; };
}
}  // namespace simsols
