#include "app/experiment/apparatus_report.h"

#include <cstdarg>
#include <cstdio>
#include <stdexcept>

namespace simsols {

std::string report_printf(const char* format, ...) {
  char buf[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

const char* run_state_word(const ProgrammeRunState& s) {
  return s.finished ? "finished" : s.interrupted ? "interrupted" : "stopped";
}

namespace {

// The reports, one per kind that has one, each in its kind's folder.
constexpr const TestReport& (*kReports[])() = {shear_box_report, oedometer_report,
                                                 triaxial_report, periodic_cell_report};

const TestReport* report_of(std::string_view kind) {
  for (const auto& report : kReports)
    if (report().kind == kind) return &report();
  return nullptr;
}

// A kind without a report of its own (an entry above is optional): its
// rows and summary.txt are written all the same; no plots, and this line.
std::string plain_text(const TestRun& run) {
  return std::string(run.kind->title) + " test " + (run.state.finished ? "finished" : "stopped") +
         ": " + std::to_string(run.state.particles) + " beads, " +
         std::to_string(run.state.steps) + " steps (its rows: " + run.programme->rows_file() + ")\n";
}

}  // namespace

bool has_test_report(std::string_view kind) { return report_of(kind) != nullptr; }

void write_test_plots(const std::string& dir, const std::string& title, const ApparatusKind& kind,
                      const ApparatusProgramme& test) {
  if (const TestReport* r = report_of(kind.name)) r->plots(dir, title, test);
}

std::string test_result_text(const TestRun& run, const std::string& dir) {
  const TestReport* report = report_of(run.kind->name);
  std::string o = report ? report->text(run) : plain_text(run);
  if (!run.state.stopped_after.empty())
    o += "  stopped at the end of the stage '" + run.state.stopped_after + "' (--stop-at)\n";
  o += "  results in " + dir + "\n";
  if (!run.state.finished) o += "  " + resume_hint(dir) + "\n";
  return o;
}

}  // namespace simsols
