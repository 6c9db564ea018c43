// What a run shows of each kind of apparatus: its plots (PNG, drawn with
// render/plot) and the lines `simsols run` prints at the end. At most one
// entry per kind of the registry (solver/apparatus/registry.h), in a table
// of its own because plots live above the solver. The entry is optional: a
// kind without one still writes its rows and summary.txt, draws no plots
// and ends with a plain line (beads, steps, its rows file); a test checks
// that the three kinds of today have one.
#pragma once

#include <string>
#include <string_view>

#include "app/experiment/apparatus_run.h"

namespace simsols {

// One kind's report: its plots of the programme's rows and summary, and
// its result lines. Each kind's is in its folder (shear_box/
// shear_report.cpp, ...), listed in apparatus_report.cpp's table.
struct TestReport {
  std::string_view kind;  // the registry's name
  void (*plots)(const std::string& dir, const std::string& title, const ApparatusProgramme& t);
  std::string (*text)(const TestRun& run);
};
const TestReport& shear_box_report();
const TestReport& oedometer_report();
const TestReport& triaxial_report();
const TestReport& periodic_cell_report();

// A kind's plots from its programme's rows and summary: write(dir, title,
// rows, summary), for TestReport::plots.
template <class Programme, auto write>
void programme_plots(const std::string& dir, const std::string& title,
                     const ApparatusProgramme& p) {
  const auto& programme = dynamic_cast<const Programme&>(p);
  write(dir, title, programme.rows(), programme.summary());
}
// printf into a string, for the result lines.
std::string report_printf(const char* format, ...) __attribute__((format(printf, 1, 2)));
// "finished", "interrupted" or "stopped".
const char* run_state_word(const ProgrammeRunState& s);

// The plots of `test` into `dir` (shear_plots.h, oedometer_plots.h,
// triaxial_plots.h), titled `title`; none for a kind without a report.
void write_test_plots(const std::string& dir, const std::string& title, const ApparatusKind& kind,
                      const ApparatusProgramme& test);

// The result lines of a run into `dir`, finished or stopped ("shear test
// finished: ...", the peak and residual, where the results are, how to
// resume).
std::string test_result_text(const TestRun& run, const std::string& dir);

// True when the kind called `kind` has a report here.
bool has_test_report(std::string_view kind);

}  // namespace simsols
