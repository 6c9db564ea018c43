// The accuracy study's cases run by a pool of workers, resumable: what
// `simsols study accuracy` (app/cli/cmd_study.cpp) runs, here where tests
// and other front ends reach it.
//
// `jobs` workers take the cases in order, each on its own OpenCL context
// and queue (opened one after the other by `open_device`), so a device that
// a small specimen leaves idle between launches runs several. A case's
// result does not depend on which worker ran it. The outputs (study.h:
// cases.csv, ensemble.csv, summary.md, the charts) are rewritten as each
// case finishes; study_state.txt keeps the finished prefix of the cases,
// which a resumed study continues after, so a case that finished after an
// unfinished one runs again on resume. A stop request (Ctrl-C) stops each
// running case at its next look, its state in its case checkpoint.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/experiment/shear_box/study.h"
#include "solver/core/cl_device.h"

namespace simsols {

struct StudyRunOptions {
  std::string out;  // the study's folder
  bool quiet = false;
  int jobs = 1;     // cases at once, each on its own device context
  std::function<std::shared_ptr<Device>()> open_device;  // one per worker
  std::function<bool()> stop_requested;                  // Ctrl-C; may be empty
};

struct StudyRunOutcome {
  std::size_t finished = 0;   // cases finished in order (the resumable prefix)
  std::size_t total = 0;
  bool interrupted = false;   // a running case was stopped; its state is in its checkpoint
  bool complete() const { return finished == total; }
};

// Runs `cases` after the `done` ones (those of a resumed study, in order).
// A worker's error ends the study (the other workers stop at their next
// look) and is rethrown.
StudyRunOutcome run_study(const StudyPreset& preset, const std::vector<StudySettings>& cases,
                          std::vector<StudyCase> done, const StudyRunOptions& options);

// The finished cases of the study in `out` (study_state.txt), to resume
// it; SceneError when there is none or it does not fit `cases`.
std::vector<StudyCase> resumed_study_cases(const std::string& out, const StudyPreset& preset,
                                           const std::vector<StudySettings>& cases);

// Case i's checkpoint: case_checkpoint.bin when the cases run one at a
// time, case_checkpoint_<i+1>.bin with jobs > 1 (several run at once).
std::filesystem::path study_case_checkpoint(const std::string& out, std::size_t i, int jobs);

}  // namespace simsols
