// One triaxial test run headless into a folder (`simsols run` on a scene
// with a [triaxial]), on the common driver of programme_run.h.
//
// Folder layout:
//   scene.toml, scene.resolved.toml   the scene as given / as used (explicit beads)
//   triaxial.csv                      one row per axial_strain / rows (TriaxialRow)
//   summary.txt                       peak and critical state, dilatancy, wall vs internal stress
//   stress_ratio.png, deviator.png, volumetric.png, e_log_p.png   triaxial_plots.h
//   paraview/, checkpoint.bin, fault.txt   as for the shear test
// summary.txt is written last: its presence means the test finished.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/experiment/apparatus_run.h"
#include "solver/apparatus/triaxial_test.h"

namespace simsols {

using TriaxialRunResult = TestRunResult<TriaxialTest>;

// Runs (or, with options.resume, resumes) the test of `scene`.
TriaxialRunResult run_triaxial(const Scene& scene, const ProgrammeRunOptions& options);
// Continues the test in options.out_dir from a loaded checkpoint.
TriaxialRunResult resume_triaxial(std::unique_ptr<Simulation> sim, const std::string& extra,
                                  const ProgrammeRunOptions& options);

}  // namespace simsols
