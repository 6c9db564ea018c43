// The title a person reads on a test's plots and pictures, made from what
// the scene sets up instead of its identifier:
//
//   "Direct shear, 6.35 mm glass beads, σ = 160 kPa"
//   "Triaxial, sand grains (D50 4.76 mm), σ₃ = 100 kPa"
//   "Oedometer, graded glass beads (D50 2 mm)"
//
// A scene without an apparatus gets its description, or its name when it
// has none. Campaign tests made from one scene get their own titles, since
// they are built from the specimen and the stress of each test.
#pragma once

#include <string>

namespace simsols {

struct Scene;

std::string test_title(const Scene& scene);

}  // namespace simsols
