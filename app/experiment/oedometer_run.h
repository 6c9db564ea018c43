// One oedometer test run headless into a folder (`simsols run` on a scene
// with an [oedometer]), on the common driver of programme_run.h.
//
// Folder layout:
//   scene.toml, scene.resolved.toml   the scene as given / as used (explicit beads)
//   oedometer.csv                     one row per check while loading (OedometerRow)
//   summary.txt                       Cc, Cs, K0, Jaky, side friction, the steps' ends
//   e_log_sigma.png, k0.png, settlement.png   oedometer_plots.h
//   paraview/                         the ParaView series (every output.dump_interval
//                                     and the end; solver/io/paraview.h)
//   checkpoint.bin                    latest state; `--resume` continues from it
//   fault.txt, fault_checkpoint.bin   only when a step ran away
// summary.txt is written last: its presence means the test finished.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/experiment/apparatus_run.h"
#include "solver/apparatus/oedometer_test.h"

namespace simsols {

using OedometerRunResult = TestRunResult<OedometerTest>;

// Runs (or, with options.resume, resumes) the test of `scene`.
OedometerRunResult run_oedometer(const Scene& scene, const ProgrammeRunOptions& options);
// Continues the test in options.out_dir from a loaded checkpoint.
OedometerRunResult resume_oedometer(std::unique_ptr<Simulation> sim, const std::string& extra,
                                    const ProgrammeRunOptions& options);

}  // namespace simsols
