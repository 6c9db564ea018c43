// One direct shear test run headless into a folder, in the shear test's own
// types, for the campaigns and studies of the shear box: run_test
// (apparatus_run.h, where the folder's layout is) with its rows and summary
// as ShearRow / ShearSummary.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/experiment/programme_run.h"
#include "solver/apparatus/shear_box/shear_programme.h"
#include "solver/scene/scene.h"

namespace simsols {

using ShearRunOptions = ProgrammeRunOptions;

struct ShearRunResult {
  ShearSummary summary;
  std::vector<ShearRow> rows;
  bool finished = false;       // false: stopped by stop_after or interrupted (resumable)
  bool interrupted = false;    // stopped by stop_requested
  long long steps = 0;
  int particles = 0;
  double dt = 0;
};

// Runs (or resumes) the test of `scene` (ignored when resuming). Throws
// SceneError / DeviceError like the other commands, and RunawayError when a
// step ran away (after saving the state before it, see save_fault).
ShearRunResult run_shear(const Scene& scene, const ShearRunOptions& options);

// Continues the test in options.out_dir from a checkpoint already loaded
// (`sim`, with the driver state `extra` it carried); prints where it
// resumed ("resumed at step N, t = ..., dx = ... mm").
ShearRunResult resume_shear(std::unique_ptr<Simulation> sim, const std::string& extra,
                            const ShearRunOptions& options);

// Where a test stands: "step N, t = ... s, shear, dx = ... mm (R rows)".
std::string where_test_is(const Simulation& sim, const ShearProgramme& test);

}  // namespace simsols
