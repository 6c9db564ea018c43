// The accuracy study's own checkpoint: the cases it finished, so that
// `simsols study accuracy --out DIR --resume` continues where a Ctrl-C,
// a kill or a crash stopped it.
//
//   DIR/study_state.txt     the finished cases (text, rewritten atomically
//                           after each case)
//   DIR/case_checkpoint.bin the shear test of the case in progress, written
//                           when the study is interrupted (checkpoint.h);
//                           the resumed case continues from it
#pragma once

#include <string>
#include <vector>

#include "app/experiment/shear_box/study.h"

namespace simsols {

// The study's identity (preset and the labels of its cases) and its
// finished cases as text, and back. parse_study_state throws SceneError
// naming `path` when the text is malformed or belongs to another study
// (other preset, other cases).
std::string study_state_text(const StudyPreset& preset, const std::vector<StudySettings>& cases,
                             const std::vector<StudyCase>& done);
std::vector<StudyCase> parse_study_state(const std::string& text, const std::string& path,
                                         const StudyPreset& preset,
                                         const std::vector<StudySettings>& cases);

}  // namespace simsols
