// The run of one apparatus' test on the common driver (programme_run.h):
// new or resumed, to its result. An apparatus brings its Test (a
// LoadingProgramme with rows() and summary(), the summary with a
// wall_seconds field) and its Outputs (a ProgrammeOutputs built from a
// Test&); oedometer_run.cpp and triaxial_run.cpp are two such.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

#include "app/experiment/programme_run.h"

namespace simsols {

template <class Test>
struct TestRunResult {
  decltype(std::declval<const Test&>().summary()) summary;
  std::decay_t<decltype(std::declval<const Test&>().rows())> rows;
  ProgrammeRunState state;
};

template <class Test, class Outputs>
TestRunResult<Test> drive_apparatus_test(Simulation& sim, Test& test,
                                         const ProgrammeRunOptions& opt, double wall_before) {
  Outputs outputs(test);
  TestRunResult<Test> r;
  r.state = drive_programme(sim, outputs, opt, wall_before);
  r.rows = test.rows();
  r.summary = test.summary();
  r.summary.wall_seconds = r.state.wall_seconds;
  return r;
}

// Continues the test in opt.out_dir from a loaded checkpoint. `is_this`
// tells whether the checkpoint's scene holds this apparatus; `what` names
// it in the refusal ("an oedometer test").
template <class Test, class Outputs>
TestRunResult<Test> resume_apparatus_test(std::unique_ptr<Simulation> sim,
                                          const std::string& state,
                                          const ProgrammeRunOptions& opt,
                                          bool (*is_this)(const Scene&), const std::string& what) {
  if (!is_this(sim->scene()))
    throw SceneError("bad_checkpoint",
                     (std::filesystem::path(opt.out_dir) / "checkpoint.bin").string(), 0,
                     "--resume", "the checkpoint is not " + what);
  Test test(*sim);
  restore_programme(test, state, opt.out_dir);
  std::fprintf(stderr, "[%s] resumed at %s\n", opt.label.c_str(),
               where_programme_is(*sim, test).c_str());
  return drive_apparatus_test<Test, Outputs>(*sim, test, opt, driver_wall_seconds(state));
}

// Runs the test of `scene`, or with opt.resume resumes the one in opt.out_dir.
template <class Test, class Outputs>
TestRunResult<Test> run_apparatus_test(const Scene& scene, const ProgrammeRunOptions& opt,
                                       bool (*is_this)(const Scene&), const std::string& what) {
  if (opt.resume) {
    std::string state;
    auto sim = load_run_checkpoint(opt, &state);
    return resume_apparatus_test<Test, Outputs>(std::move(sim), state, opt, is_this, what);
  }
  Simulation sim(opt.device, scene);
  Test test(sim);
  start_run_folder(scene, opt.out_dir);
  return drive_apparatus_test<Test, Outputs>(sim, test, opt, 0);
}

}  // namespace simsols
