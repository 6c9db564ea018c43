// A graded specimen's record, written when its run starts: grading.txt
// (D10, D30, D50, D60, Cu and Cc of the beads drawn against the asked
// curve, with the sampling error; grading.h) and grading.png (the two sieve
// curves, percent passing by mass against size on a log axis). Nothing is
// written for a specimen of one size.
#pragma once

#include <string>

#include "solver/scene/scene.h"

namespace simsols {

// The specimen's table of the scene's apparatus; nullptr when none or not
// graded.
const Specimen* graded_specimen(const Scene& scene);

void write_grading_files(const Scene& scene, const std::string& dir);

}  // namespace simsols
