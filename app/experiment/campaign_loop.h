// The loop every campaign runs, whatever its apparatus (the shear box's
// programme, shear_box/campaign.h; the triaxial cell's confining stresses,
// triaxial/triaxial_campaign.h): what to run (all tests, one array task,
// or none when collecting), the tests kept when finished earlier, the
// others run or resumed from their checkpoints, with progress and an ETA
// over the whole campaign.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/experiment/programme_run.h"
#include "solver/core/cl_device.h"

namespace simsols {

// What a campaign run does with its tests: all of them (the default);
// `only` one of them (a cluster's array task, cluster.h: the report is
// then left to the collecting job); or, with `collect`, none: every test
// must have finished (elsewhere) and the report is written from their
// folders.
struct CampaignRun {
  std::shared_ptr<Device> device;
  std::function<bool()> stop_requested;  // checked between steps
  bool quiet = false;
  std::optional<size_t> only;
  bool collect = false;
  bool writes_report() const { return !only; }
};

struct CampaignOutcome {
  bool interrupted = false;
  size_t interrupted_test = 0;  // index of the test that was stopped
  double seconds = 0;           // wall time of the tests run now
};

// The loop every campaign runs, whatever its apparatus: for each test, keep
// it when finished earlier, else run it (resuming its checkpoint when its
// rows file is there too), with progress and an ETA over the whole
// campaign. Test k's callbacks: its estimated cost (particle-steps), its
// folder and name, `keep` (read back a test finished earlier), `run` (true
// when interrupted) and `print` its result. campaign_loop() fills the
// first three from a test list.
struct CampaignLoop {
  size_t count = 0;
  std::string what;       // "tests", "triaxial tests"
  std::string rows_file;  // "shear.csv", "triaxial.csv"
  // Particle-steps of the work after this loop (a calibration's later
  // rounds): the ETA covers it too.
  double later_cost = 0;
  std::function<double(size_t)> cost;
  std::function<std::filesystem::path(size_t)> dir;
  std::function<std::string(size_t)> name;
  std::function<void(size_t)> keep;
  // Fills in the test's result from a run with these options; true when
  // the run was interrupted.
  std::function<bool(size_t, ProgrammeRunOptions&)> run;
  std::function<void(size_t)> print;
};
template <class Test>
CampaignLoop campaign_loop(std::vector<Test>& tests, std::string what, std::string rows_file) {
  CampaignLoop loop;
  loop.count = tests.size();
  loop.what = std::move(what);
  loop.rows_file = std::move(rows_file);
  loop.cost = [&tests](size_t k) { return tests[k].cost; };
  loop.dir = [&tests](size_t k) { return tests[k].dir; };
  loop.name = [&tests](size_t k) { return tests[k].scene.name; };
  return loop;
}
// Throws UsageError naming --task when `run.only` is not a test's index,
// and naming --collect when collecting tests that have not finished.
CampaignOutcome run_campaign_loop(const CampaignLoop& loop, const CampaignRun& run);

}  // namespace simsols
