// One apparatus' test run headless into a folder, whatever the apparatus:
// the one path from a scene to its result that `simsols run`, Python, the
// campaigns and the studies share.
//
// The scene's kind (solver/apparatus/registry.h) makes the test
// (ApparatusProgramme); the common driver (programme_run.h) steps it with
// progress, checkpoints, Ctrl-C and --stop-after; the kind's report
// (apparatus_report.h) draws its plots. Folder layout, for every apparatus:
//   scene.toml, scene.resolved.toml   the scene as given / as used (explicit beads)
//   <rows file>                       shear.csv, oedometer.csv, triaxial.csv: one row
//                                     per measurement, with units
//   summary.txt                       the test's result (written last: its presence
//                                     means the test finished)
//   *.png                             the kind's plots (apparatus_report.h)
//   density.csv, density.png, packing.txt   the specimen's preparation
//   tamping.csv, tamping_state.txt          layered tamping; the state only while it runs
//   paraview/                         the ParaView series (solver/io/paraview.h)
//   checkpoint.bin                    latest state; `--resume` continues from it
//   fault.txt, fault_checkpoint.bin   only when a step ran away (guard.h)
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "app/experiment/programme_run.h"
#include "solver/apparatus/registry.h"

namespace simsols {

// A test run (or stopped): the simulation, its test and how the run ended.
struct TestRun {
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<ApparatusProgramme> programme;  // on *sim
  const ApparatusKind* kind = nullptr;
  ProgrammeRunState state;
};

// Runs the test of `scene` (which has an apparatus) into options.out_dir,
// or with options.resume continues the one there.
TestRun run_test(const Scene& scene, const ProgrammeRunOptions& options);

// Continues the test in options.out_dir from a checkpoint already loaded
// (`sim`, with the driver state `extra` it carried); SceneError when its
// scene has no apparatus.
TestRun resume_test(std::unique_ptr<Simulation> sim, const std::string& extra,
                    const ProgrammeRunOptions& options);

// The path every front end takes from a scene to its result: the scene
// placed when it was only read (place_scene, solver/io/scene_toml.h: its
// generators' spheres, the apparatus' walls and specimen), the specimen
// prepared when the scene asks it (a relative density, tamping, radius
// expansion: prepare_to_relative_density, specimen_report.h, its lines
// to `log`), then run_test. With options.resume `scene` is not used. The
// preparation asks options.stop_requested between chunks of steps and
// throws PreparationStopped (prep_log.h) when it says so: nothing of the
// test is written yet, and the same command prepares it again (a layered
// tamping from the last layer it finished, tamping_state.h).
TestRun run_scene_test(Scene scene, const ProgrammeRunOptions& options,
                       const std::function<void(const std::string&)>& log);

// A finished or stopped run's rows and summary in the test's own types.
template <class Test>
struct TestRunResult {
  decltype(std::declval<const Test&>().summary()) summary;
  std::decay_t<decltype(std::declval<const Test&>().rows())> rows;
  ProgrammeRunState state;
};
template <class Test>
TestRunResult<Test> typed_result(const TestRun& run) {
  const Test& test = dynamic_cast<const Test&>(*run.programme);
  TestRunResult<Test> r{test.summary(), test.rows(), run.state};
  r.summary.wall_seconds = run.state.wall_seconds;
  return r;
}

}  // namespace simsols
